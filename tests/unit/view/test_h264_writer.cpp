// The H.264 writer: what it writes reads back as H.264, every frame, at the rate asked and close to the
// frames given; what it cannot do is a message, not a crash.
#include <gtest/gtest.h>

#include <filesystem>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "h264_writer.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

// A frame with edges and text that moves, as an annotated frame has: a plain colour would pass anything.
cv::Mat frame(int i) {
  cv::Mat f(240, 320, CV_8UC3, cv::Scalar(40, 90, 160));
  cv::rectangle(f, cv::Rect(20 + 3 * i, 30, 80, 120), cv::Scalar(0, 0, 255), 2);
  cv::circle(f, cv::Point(220, 120 + i), 30, cv::Scalar(255, 255, 255), cv::FILLED);
  cv::putText(f, "seq " + std::to_string(i), cv::Point(10, 220), cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(0, 255, 255), 2);
  return f;
}

TEST(H264Writer, EveryFrameReadsBackAsH264AtTheRateAskedCloseToWhatWasGiven) {
  const fs::path dir = fs::temp_directory_path() / ("gpilot_h264_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string mp4 = (dir / "v.mp4").string();
  {
    H264Writer w;
    ASSERT_EQ(w.open(mp4, cv::Size(320, 240), 12.5), "");
    for (int i = 0; i < 30; ++i) w.write(frame(i));
    w.close();
    EXPECT_FALSE(w.is_open());
  }
  cv::VideoCapture cap(mp4, cv::CAP_FFMPEG);
  ASSERT_TRUE(cap.isOpened());
  const int fourcc = static_cast<int>(cap.get(cv::CAP_PROP_FOURCC));
  EXPECT_TRUE(fourcc == cv::VideoWriter::fourcc('a', 'v', 'c', '1') || fourcc == cv::VideoWriter::fourcc('h', '2', '6', '4'))
      << "fourcc " << std::string(reinterpret_cast<const char*>(&fourcc), 4);
  EXPECT_NEAR(cap.get(cv::CAP_PROP_FPS), 12.5, 0.01);
  int n = 0;
  cv::Mat f;
  double worst_psnr = 1e9;
  while (cap.read(f)) {
    ASSERT_EQ(f.size(), cv::Size(320, 240));
    worst_psnr = std::min(worst_psnr, cv::PSNR(f, frame(n)));
    ++n;
  }
  EXPECT_EQ(n, 30);
  EXPECT_GT(worst_psnr, 30.0) << "frames read back far from the ones written";
  fs::remove_all(dir);
}

TEST(H264Writer, WhatItCannotDoIsAMessage) {
  H264Writer w;
  EXPECT_NE(w.open("/nonexistent-dir/v.mp4", cv::Size(64, 48), 25.0), "");
  EXPECT_FALSE(w.is_open());
  EXPECT_NE(w.open((fs::temp_directory_path() / "gpilot_odd.mp4").string(), cv::Size(63, 48), 25.0).find("not even"),
            std::string::npos);
  H264Params slow;
  slow.preset = "no-such-preset";
  EXPECT_NE(w.open((fs::temp_directory_path() / "gpilot_preset.mp4").string(), cv::Size(64, 48), 25.0, slow), "");
  EXPECT_FALSE(w.is_open());
  EXPECT_THROW(w.write(cv::Mat(48, 64, CV_8UC3)), std::runtime_error);
  w.close();  // nothing open: nothing to do
  fs::remove(fs::temp_directory_path() / "gpilot_odd.mp4");
  fs::remove(fs::temp_directory_path() / "gpilot_preset.mp4");
}

}  // namespace
}  // namespace gpilot
