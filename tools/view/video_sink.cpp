#include "video_sink.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace gpilot {
namespace {
constexpr size_t kFramesForRate = 60;     // 2.4 s at 25 fps
constexpr size_t kStartupFramesSkipped = 10;  // a source's first frames are often late (loading, warm-up)
constexpr double kDefaultFps = 25.0;  // the paper's camera rate, when the frames do not tell
}  // namespace

double rate_from_utimes(const std::vector<int64_t>& utimes, double fallback) {
  // The mean rate over the window: a source that stalls and then catches up in a burst (a paced loop
  // behind schedule) has short intervals that a median would take for its rate.
  if (utimes.size() < 2 || utimes.back() <= utimes.front()) return fallback;
  const double hz = 1e6 * static_cast<double>(utimes.size() - 1) / static_cast<double>(utimes.back() - utimes.front());
  return std::clamp(hz, 1.0, 240.0);
}

VideoSink::VideoSink(std::string mp4, double fps, std::string png_dir, int png_every)
    : mp4_(std::move(mp4)), fps_(fps), png_dir_(std::move(png_dir)), png_every_(png_every) {}

VideoSink::~VideoSink() {
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpilot-view: %s\n", e.what());
  }
}

void VideoSink::open(const cv::Size& size) {
  // H.264 needs even sides; frames are padded by a row/column when odd.
  size_ = cv::Size(size.width + size.width % 2, size.height + size.height % 2);
  const std::string h264_failed = h264_.open(mp4_, size_, fps_);
  if (h264_failed.empty()) {
    fourcc_ = "avc1";
    return;
  }
  std::fprintf(stderr, "gpilot-view: %s: %s; trying OpenCV's writer (mp4v)\n", mp4_.c_str(), h264_failed.c_str());
  writer_.open(mp4_, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps_, size_);
  if (!writer_.isOpened()) throw std::runtime_error("cannot open " + mp4_ + " for writing (" + h264_failed + "; nor mp4v)");
  fourcc_ = "mp4v";
}

void VideoSink::encode(const cv::Mat& annotated) {
  cv::Mat f = annotated;
  const cv::Size odd_fix(f.cols + f.cols % 2, f.rows + f.rows % 2);
  if (odd_fix != f.size())
    cv::copyMakeBorder(f, f, 0, odd_fix.height - f.rows, 0, odd_fix.width - f.cols, cv::BORDER_REPLICATE);
  if (f.size() != size_) cv::resize(f, f, size_, 0, 0, cv::INTER_AREA);
  if (h264_.is_open())
    h264_.write(f);
  else
    writer_.write(f);
  ++written_;
}

void VideoSink::write(const cv::Mat& annotated, int64_t seq, int64_t utime) {
  if (closed_) throw std::runtime_error("write after close");
  if (png_every_ > 0 && seen_ % png_every_ == 0) {
    char name[64];
    std::snprintf(name, sizeof name, "/frame_%06lld.png", static_cast<long long>(seq));
    const std::string path = png_dir_ + name;
    if (!cv::imwrite(path, annotated)) throw std::runtime_error("cannot write " + path);
    ++pngs_;
  }
  ++seen_;
  if (mp4_.empty()) return;
  if (h264_.is_open() || writer_.isOpened()) {
    encode(annotated);
    return;
  }
  waiting_.emplace_back(annotated.clone(), utime);
  if (fps_ > 0 || waiting_.size() >= kFramesForRate) start_writer();
}

void VideoSink::start_writer() {
  if (fps_ <= 0) {
    std::vector<int64_t> t;
    const size_t skip = waiting_.size() > 2 * kStartupFramesSkipped ? kStartupFramesSkipped : 0;
    for (size_t i = skip; i < waiting_.size(); ++i) t.push_back(waiting_[i].second);
    fps_ = rate_from_utimes(t, kDefaultFps);
  }
  const auto frames = std::move(waiting_);  // a failed open drops them: it is not retried at close
  waiting_.clear();
  open(frames.front().first.size());
  for (const auto& w : frames) encode(w.first);
}

void VideoSink::close() {
  if (closed_) return;
  closed_ = true;
  if (!waiting_.empty()) start_writer();
  if (writer_.isOpened()) writer_.release();
  h264_.close();
}

}  // namespace gpilot
