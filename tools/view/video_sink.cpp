#include "video_sink.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace gpilot {
namespace {
constexpr size_t kFramesForRate = 10;
constexpr double kDefaultFps = 25.0;  // the paper's camera rate, when the frames do not tell
}  // namespace

double rate_from_utimes(const std::vector<int64_t>& utimes, double fallback) {
  std::vector<int64_t> d;
  for (size_t i = 1; i < utimes.size(); ++i)
    if (utimes[i] > utimes[i - 1]) d.push_back(utimes[i] - utimes[i - 1]);
  if (d.empty()) return fallback;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  const double hz = 1e6 / static_cast<double>(d[d.size() / 2]);
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
  for (const char* cc : {"avc1", "mp4v"}) {
    writer_.open(mp4_, cv::CAP_FFMPEG, cv::VideoWriter::fourcc(cc[0], cc[1], cc[2], cc[3]), fps_, size_);
    if (writer_.isOpened()) {
      fourcc_ = cc;
      return;
    }
  }
  throw std::runtime_error("cannot open " + mp4_ + " for writing with the FFMPEG backend (avc1 or mp4v)");
}

void VideoSink::encode(const cv::Mat& annotated) {
  cv::Mat f = annotated;
  const cv::Size odd_fix(f.cols + f.cols % 2, f.rows + f.rows % 2);
  if (odd_fix != f.size())
    cv::copyMakeBorder(f, f, 0, odd_fix.height - f.rows, 0, odd_fix.width - f.cols, cv::BORDER_REPLICATE);
  if (f.size() != size_) cv::resize(f, f, size_, 0, 0, cv::INTER_AREA);
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
  if (writer_.isOpened()) {
    encode(annotated);
    return;
  }
  waiting_.emplace_back(annotated.clone(), utime);
  if (fps_ > 0 || waiting_.size() >= kFramesForRate) start_writer();
}

void VideoSink::start_writer() {
  if (fps_ <= 0) {
    std::vector<int64_t> t;
    for (const auto& w : waiting_) t.push_back(w.second);
    fps_ = rate_from_utimes(t, kDefaultFps);
  }
  open(waiting_.front().first.size());
  for (const auto& w : waiting_) encode(w.first);
  waiting_.clear();
}

void VideoSink::close() {
  if (closed_) return;
  closed_ = true;
  if (!waiting_.empty()) start_writer();
  if (writer_.isOpened()) writer_.release();
}

}  // namespace gpilot
