// Camera, video file and image folder sources (see frame_sources.hpp).
#include "frame_sources.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

namespace gpilot {
namespace {

std::string fmt_fps(double fps) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", fps);
  return buf;
}

// Sources give BGR: grey or BGRA inputs are converted.
void to_bgr(cv::Mat& m) {
  if (m.channels() == 1) cv::cvtColor(m, m, cv::COLOR_GRAY2BGR);
  else if (m.channels() == 4) cv::cvtColor(m, m, cv::COLOR_BGRA2BGR);
}

}  // namespace

VideoFileSource::VideoFileSource(const std::string& path, bool loop, bool jpeg_passthrough)
    : path_(path), loop_(loop), jpeg_passthrough_(jpeg_passthrough) {
  if (!std::filesystem::is_regular_file(path_)) throw SourceError("video file '" + path_ + "' does not exist");
  if (!open()) throw SourceError("FFmpeg cannot open video file '" + path_ + "' (not a video, or a codec it lacks)");
}

bool VideoFileSource::open() {
  cap_.release();
  if (!cap_.open(path_, cv::CAP_FFMPEG)) return false;
  const double fps = cap_.get(cv::CAP_PROP_FPS);
  fps_ = std::isfinite(fps) && fps > 0.1 && fps < 1000 ? fps : 25.0;  // unknown rate: the paper's 25
  count_ = static_cast<int64_t>(std::max(0.0, cap_.get(cv::CAP_PROP_FRAME_COUNT)));
  width_ = static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_WIDTH));
  height_ = static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_HEIGHT));
  in_pass_ = 0;
  // MJPEG: each stored frame is a JPEG already. Read undecoded (OpenCV's FFmpeg raw mode, set before the first
  // read), it is published without a decode and a re-encode.
  const int fourcc = static_cast<int>(cap_.get(cv::CAP_PROP_FOURCC));
  const bool mjpeg = fourcc == cv::VideoWriter::fourcc('M', 'J', 'P', 'G') || fourcc == cv::VideoWriter::fourcc('m', 'j', 'p', 'g');
  raw_jpeg_ = jpeg_passthrough_ && mjpeg && cap_.set(cv::CAP_PROP_FORMAT, -1);
  return true;
}

ReadStatus VideoFileSource::read(cv::Mat& out, std::string& why) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (cap_.read(out) && !out.empty()) {
      if (raw_jpeg_) out = out.reshape(1, 1);  // the packet's bytes, one row
      else to_bgr(out);
      ++frames_;
      ++in_pass_;
      return ReadStatus::Frame;
    }
    // The end: loop back once, unless the file gave nothing at all this pass.
    if (!loop_ || in_pass_ == 0 || !open()) break;
  }
  why = "end of video file '" + path_ + "' after " + std::to_string(frames_) + " frames";
  return ReadStatus::End;
}

std::string VideoFileSource::describe() const {
  return "video '" + path_ + "' (" + std::to_string(width_) + "x" + std::to_string(height_) +
         (raw_jpeg_ ? " MJPEG, its JPEG frames passed through" : "") + " @ " + fmt_fps(fps_) + " fps, " +
         std::to_string(count_) + " frames" + (loop_ ? ", looping)" : ")");
}

ImageFolderSource::ImageFolderSource(const std::string& dir, double fps, bool loop) : dir_(dir), fps_(fps), loop_(loop) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir_)) throw SourceError("image folder '" + dir_ + "' does not exist");
  static const std::vector<std::string> kExt = {".png", ".jpg", ".jpeg", ".bmp", ".ppm", ".pgm", ".tif", ".tiff"};
  for (const auto& e : fs::directory_iterator(dir_)) {
    if (!e.is_regular_file()) continue;
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (std::find(kExt.begin(), kExt.end(), ext) != kExt.end()) files_.push_back(e.path().string());
  }
  std::sort(files_.begin(), files_.end());
  if (files_.empty()) throw SourceError("image folder '" + dir_ + "' holds no image file (png, jpg, bmp, ppm, pgm, tif)");
}

ReadStatus ImageFolderSource::read(cv::Mat& out, std::string& why) {
  if (next_ >= files_.size()) {
    if (!loop_) {
      why = "end of image folder '" + dir_ + "' after " + std::to_string(frames_) + " frames";
      return ReadStatus::End;
    }
    next_ = 0;
  }
  const std::string& file = files_[next_++];
  out = cv::imread(file, cv::IMREAD_UNCHANGED);
  if (out.empty() || out.depth() != CV_8U) {
    why = "image '" + file + "' does not decode as an 8-bit image";
    return ReadStatus::Skip;
  }
  to_bgr(out);
  ++frames_;
  return ReadStatus::Frame;
}

std::string ImageFolderSource::describe() const {
  return "images '" + dir_ + "' (" + std::to_string(files_.size()) + " files @ " + fmt_fps(fps_) + " fps" +
         (loop_ ? ", looping)" : ")");
}

CameraSource::CameraSource(int index, int width, int height, double fps)
    : index_(index), asked_w_(width), asked_h_(height), asked_fps_(fps) {}

bool CameraSource::open(std::string& why) {
  cap_.release();
  if (!cap_.open(index_, cv::CAP_V4L2)) {
    why = "cannot open camera " + std::to_string(index_) + " (/dev/video" + std::to_string(index_) + ")";
    return false;
  }
  cap_.set(cv::CAP_PROP_FRAME_WIDTH, asked_w_);
  cap_.set(cv::CAP_PROP_FRAME_HEIGHT, asked_h_);
  cap_.set(cv::CAP_PROP_FPS, asked_fps_);
  got_w_ = static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_WIDTH));
  got_h_ = static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_HEIGHT));
  got_fps_ = cap_.get(cv::CAP_PROP_FPS);
  return true;
}

ReadStatus CameraSource::read(cv::Mat& out, std::string& why) {
  if (!cap_.isOpened() || !cap_.read(out) || out.empty()) {
    cap_.release();
    why = "camera " + std::to_string(index_) + " delivers no frames (unplugged?)";
    return ReadStatus::Lost;
  }
  to_bgr(out);
  ++frames_;
  return ReadStatus::Frame;
}

std::string CameraSource::describe() const {
  return "camera " + std::to_string(index_) + ": got " + std::to_string(got_w_) + "x" + std::to_string(got_h_) + " @ " +
         fmt_fps(got_fps_) + " fps (asked " + std::to_string(asked_w_) + "x" + std::to_string(asked_h_) + " @ " +
         fmt_fps(asked_fps_) + ")";
}

}  // namespace gpilot
