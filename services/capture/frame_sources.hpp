// Where real frames come from: a V4L2 camera, a video file (OpenCV's FFmpeg backend) or a folder of images.
// Plain I/O classes, no LCM and no clock: the adapter paces them and stamps utime.
//
// Time of a frame from a file (`media_time_s`): frame index / the file's frame rate (video) or / --fps
// (images), counted from the first frame and continuing across --loop. The adapter derives utime from it,
// so replaying the same file gives the same utimes.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

namespace gpilot {

class SourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ReadStatus {
  Frame,  //!< a frame is in `out`
  Skip,   //!< this item was unusable (a bad image in a folder); `why` says so; try the next
  End,    //!< no more frames (file ended, not looping)
  Lost,   //!< the device stopped delivering (camera unplugged); reopen to retry
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual ReadStatus read(cv::Mat& out, std::string& why) = 0;
  // Whether read() gives the source's own JPEG bytes (a 1-row CV_8UC1 Mat) instead of BGR pixels.
  virtual bool gives_jpeg() const { return false; }
  virtual std::string describe() const = 0;  //!< what is open, for logs and HEALTH
  virtual double fps() const = 0;            //!< frame rate the frames should be paced at
  int64_t frames_read() const { return frames_; }
  double media_time_s() const { return fps() > 0 ? static_cast<double>(frames_ - 1) / fps() : 0.0; }  //!< of the last frame

 protected:
  int64_t frames_ = 0;
};

// A video file via cv::CAP_FFMPEG (GStreamer is broken on Debian 12's OpenCV, see STACK.md).
class VideoFileSource : public FrameSource {
 public:
  // Throws SourceError with the reason when the file is missing or FFmpeg cannot open it. With jpeg_passthrough,
  // an MJPEG video's frames are read as they are stored (FFmpeg's raw packets, each a JPEG), not decoded.
  VideoFileSource(const std::string& path, bool loop, bool jpeg_passthrough = false);
  ReadStatus read(cv::Mat& out, std::string& why) override;
  bool gives_jpeg() const override { return raw_jpeg_; }
  std::string describe() const override;
  double fps() const override { return fps_; }
  int64_t frame_count() const { return count_; }  //!< as the container reports it (may be 0 if unknown)

 private:
  bool open();
  std::string path_;
  bool loop_, jpeg_passthrough_;
  bool raw_jpeg_ = false;
  int width_ = 0, height_ = 0;
  cv::VideoCapture cap_;
  double fps_ = 25.0;
  int64_t count_ = 0;
  int64_t in_pass_ = 0;  // frames read since the file was (re)opened
};

// Every image file in a folder (png, jpg, jpeg, bmp, ppm, pgm, tif, tiff), in name order.
class ImageFolderSource : public FrameSource {
 public:
  // Throws SourceError when the folder is missing or holds no image file.
  ImageFolderSource(const std::string& dir, double fps, bool loop);
  ReadStatus read(cv::Mat& out, std::string& why) override;
  std::string describe() const override;
  double fps() const override { return fps_; }
  const std::vector<std::string>& files() const { return files_; }

 private:
  std::string dir_;
  double fps_;
  bool loop_;
  std::vector<std::string> files_;
  size_t next_ = 0;
};

// A V4L2 camera, asked for a size and rate; it reports what it got.
class CameraSource : public FrameSource {
 public:
  CameraSource(int index, int width, int height, double fps);
  // (Re)opens the device; false with the reason in `why` when it cannot.
  bool open(std::string& why);
  bool is_open() const { return cap_.isOpened(); }
  ReadStatus read(cv::Mat& out, std::string& why) override;
  std::string describe() const override;
  double fps() const override { return got_fps_ > 0 ? got_fps_ : asked_fps_; }

 private:
  int index_, asked_w_, asked_h_;
  double asked_fps_;
  int got_w_ = 0, got_h_ = 0;
  double got_fps_ = 0.0;
  cv::VideoCapture cap_;
};

}  // namespace gpilot
