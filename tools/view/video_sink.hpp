// Where gpilot-view's annotated frames go when there is no window: an MP4 and/or every N-th frame as a PNG.
// The MP4 is H.264 at x264's veryfast preset (h264_writer.hpp); without libx264, OpenCV's FFMPEG writer
// (mp4v; GStreamer is unusable on this stack, see STACK.md §5).
//
// The MP4 is opened at the first frame with that frame's size; later frames of another size are scaled
// to it. Without a given rate, the rate is the mean rate of frames 10..59's utimes (frames are
// buffered until then; the very first frames of a source are often late). close() must run for the MP4 to be playable (it writes the index).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "h264_writer.hpp"

namespace gpilot {

class VideoSink {
 public:
  // mp4: "" for none; fps <= 0: from the frames' utimes; png_every <= 0: no PNGs.
  VideoSink(std::string mp4, double fps, std::string png_dir, int png_every);
  ~VideoSink();
  VideoSink(const VideoSink&) = delete;
  VideoSink& operator=(const VideoSink&) = delete;

  // Throws std::runtime_error when the MP4 cannot be opened or a PNG cannot be written.
  void write(const cv::Mat& annotated, int64_t seq, int64_t utime);
  void close();

  int64_t frames_written() const { return written_; }
  int64_t pngs_written() const { return pngs_; }
  double fps() const { return fps_; }
  const std::string& fourcc() const { return fourcc_; }

 private:
  void open(const cv::Size& size);
  void start_writer();  // opens the MP4 once the rate is known and writes the frames held for it
  void encode(const cv::Mat& annotated);

  std::string mp4_;
  double fps_;
  std::string png_dir_;
  int png_every_;
  H264Writer h264_;
  cv::VideoWriter writer_;  // the fallback
  cv::Size size_;
  std::string fourcc_;
  std::vector<std::pair<cv::Mat, int64_t>> waiting_;  // frames held until the rate is known
  int64_t seen_ = 0, written_ = 0, pngs_ = 0;
  bool closed_ = false;
};

// The mean rate of increasing utimes in Hz (first to last), or fallback when it cannot be told.
double rate_from_utimes(const std::vector<int64_t>& utimes, double fallback);

}  // namespace gpilot
