// The MP4/PNG sink: the rate from the frames' times, odd sizes, every frame in the file, PNG every N.
#include <gtest/gtest.h>

#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "video_sink.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

TEST(VideoSink, RateIsTheMeanRateEvenWhenFramesComeInBursts) {
  // A stall then a burst: 5 frames over 200 ms is 20 Hz, whatever the single intervals.
  EXPECT_DOUBLE_EQ(rate_from_utimes({0, 120000, 150000, 180000, 200000}, 7.0), 20.0);
  EXPECT_DOUBLE_EQ(rate_from_utimes({0}, 7.0), 7.0);
  EXPECT_DOUBLE_EQ(rate_from_utimes({5, 5, 5}, 7.0), 7.0);
}

TEST(VideoSink, OddSizedFramesAllReachTheMp4AndEveryNthThePngs) {
  const fs::path dir = fs::temp_directory_path() / ("gpilot_video_sink_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string mp4 = (dir / "v.mp4").string();
  {
    VideoSink sink(mp4, 0.0, dir.string(), 4);
    for (int i = 0; i < 13; ++i) {
      cv::Mat f(121, 161, CV_8UC3, cv::Scalar(i * 10, 100, 50));
      sink.write(f, 100 + i, 1000000 + i * 50000);  // 20 Hz
    }
    sink.close();
    EXPECT_EQ(sink.frames_written(), 13);
    EXPECT_EQ(sink.pngs_written(), 4);  // frames 0, 4, 8, 12
    EXPECT_DOUBLE_EQ(sink.fps(), 20.0);
  }
  cv::VideoCapture cap(mp4, cv::CAP_FFMPEG);
  ASSERT_TRUE(cap.isOpened());
  EXPECT_NEAR(cap.get(cv::CAP_PROP_FPS), 20.0, 0.01);
  EXPECT_EQ(cap.get(cv::CAP_PROP_FRAME_WIDTH), 162);  // padded to even sides for H.264
  int n = 0;
  cv::Mat f;
  while (cap.read(f)) ++n;
  EXPECT_EQ(n, 13);
  const cv::Mat png = cv::imread((dir / "frame_000108.png").string());
  ASSERT_FALSE(png.empty());
  EXPECT_EQ(png.size(), cv::Size(161, 121));  // PNGs keep the frame as drawn
  fs::remove_all(dir);
}

TEST(VideoSink, AnUnwritablePathIsAnError) {
  VideoSink sink("/nonexistent-dir/v.mp4", 25.0, "", 0);
  EXPECT_THROW(sink.write(cv::Mat(20, 20, CV_8UC3, cv::Scalar::all(0)), 0, 0), std::runtime_error);
}

}  // namespace
}  // namespace gpilot
