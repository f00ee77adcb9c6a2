// An H.264 MP4 written through FFmpeg's libavformat/libavcodec (libx264) with the encoder's speed preset
// chosen: OpenCV's FFMPEG writer opens libx264 at its default "medium" preset and passes no options to it
// (avcodec_open2 without a dictionary in 4.6), which cost gpilot-view 28 ms of CPU per 640x480 frame live,
// 71 % of a core beside a pipeline that needs both cores (tools/view/README.md has the figures).
#pragma once

#include <string>

#include <opencv2/core.hpp>

struct AVFormatContext;
struct AVCodecContext;
struct AVStream;
struct AVFrame;
struct AVPacket;
struct SwsContext;

namespace gpilot {

struct H264Params {
  std::string preset = "veryfast";  //!< x264 speed preset: medium 18 ms a 640x602 frame, veryfast 7.7 ms, smaller file
  int crf = 23;                     //!< x264 constant rate factor (its default): quality, not a bitrate
  int threads = 1;                  //!< encoder threads: one, so the viewer never takes both cores
};

class H264Writer {
 public:
  H264Writer() = default;
  ~H264Writer();
  H264Writer(const H264Writer&) = delete;
  H264Writer& operator=(const H264Writer&) = delete;

  // Opens path for frames of size (even sides) at fps. Returns "" or why it could not (no libx264 encoder,
  // an unwritable path, ...); nothing is left open on failure.
  std::string open(const std::string& path, cv::Size size, double fps, const H264Params& params = {});
  bool is_open() const { return codec_ != nullptr; }
  // One BGR frame of the opened size. Throws std::runtime_error when the encoder or the file fails.
  void write(const cv::Mat& bgr);
  // Flushes the encoder and writes the index (the MP4 is not playable without it). Throws like write().
  void close();

 private:
  void drain();  // writes every packet the encoder has ready
  void release();

  AVFormatContext* format_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVStream* stream_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* to_yuv_ = nullptr;
  cv::Size size_;
  long long next_pts_ = 0;
};

}  // namespace gpilot
