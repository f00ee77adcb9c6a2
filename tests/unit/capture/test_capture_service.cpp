// The capture loop in-process on memq:// (no network): a video written with cv::VideoWriter reads back with
// the right frame count, sizes and growing utimes (the bus clock when read); a missing file is a clear error in HEALTH; a bad image in
// a folder is a counted rejection; the synthetic world publishes CAMERA and GROUND_TRUTH with the same seq and
// utime and flies its camera with VEHICLE_STATE; an MJPEG video's own JPEG frames are published as stored.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <unistd.h>

#include "capture_service.hpp"
#include "clock.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/vehicle_state_t.hpp"
#include "image_codec.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

struct Received {
  std::vector<image_t> frames;
  std::vector<ground_truth_t> truths;
  std::vector<health_t> health;
};

// Subscribes the test's view of the bus on the same memq node the loop publishes on.
void listen(BusNode& node, Received& r) {
  node.subscribe<image_t>("CAMERA", [&r](const image_t& m, int64_t) { r.frames.push_back(m); });
  node.subscribe<ground_truth_t>("GROUND_TRUTH", [&r](const ground_truth_t& m, int64_t) { r.truths.push_back(m); });
  node.subscribe<health_t>("HEALTH", [&r](const health_t& m, int64_t) { r.health.push_back(m); });
}

void drain(BusNode& node) { node.drain(); }

class CaptureService : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gpilot-capture-test-" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // An MJPG video of n frames at fps, frame i a flat grey of brightness i * step; returns its path.
  std::string write_clip(const std::string& name, int n, double fps, cv::Size size, int step) {
    const std::string path = (dir_ / name).string();
    cv::VideoWriter w(path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, size);
    EXPECT_TRUE(w.isOpened());
    for (int i = 0; i < n; ++i) w.write(cv::Mat(size, CV_8UC3, cv::Scalar::all(i * step)));
    return path;
  }

  static CaptureOptions video(const std::string& path) {
    CaptureOptions o;
    o.kind = CaptureOptions::Kind::Video;
    o.source = path;
    o.as_fast_as_possible = true;
    return o;
  }

  fs::path dir_;
};

// Raw frames (the default is JPEG): pixels compared exactly.
Config raw_frames() { return Config::from_string("capture:\n  pixel_format: BGR8\n"); }

TEST_F(CaptureService, VideoFileReadsBackEveryFrame) {
  // GIVEN a 60-frame 320x240 video at 20 fps, frame i showing i in its brightness
  const std::string path = write_clip("clip.avi", 60, 20.0, {320, 240}, 4);
  BusNode node("test", "memq://");
  Received r;
  listen(node, r);
  // WHEN it is captured
  EXPECT_EQ(run_capture(raw_frames(), video(path), node), 0);
  drain(node);
  // THEN 60 frames of the right size, seq 0..59, utimes on the bus clock and growing, content in order
  ASSERT_EQ(r.frames.size(), 60u);
  for (size_t i = 0; i < r.frames.size(); ++i) {
    const image_t& m = r.frames[i];
    EXPECT_EQ(m.width, 320);
    EXPECT_EQ(m.height, 240);
    EXPECT_EQ(m.pixel_format, image_t::PIXEL_FORMAT_BGR8);
    EXPECT_EQ(m.seq, static_cast<int64_t>(i));
    if (i) {
      EXPECT_GT(m.utime, r.frames[i - 1].utime);
    }
    cv::Mat f;
    ASSERT_EQ(image_to_mat(m, f), "");
    EXPECT_NEAR(cv::mean(f)[0], i * 4.0, 3.0);
  }
  EXPECT_TRUE(r.frames.empty() || r.truths.empty());  // no ground truth for a file
  ASSERT_FALSE(r.health.empty());
  EXPECT_EQ(r.health.back().state, health_t::STATE_STOPPING);
  EXPECT_NE(r.health.back().state_detail.find("end of video file"), std::string::npos) << r.health.back().state_detail;
}

TEST_F(CaptureService, LoopedVideoKeepsCountingUntilTheDuration) {
  CaptureOptions o = video(write_clip("short.avi", 10, 10.0, {64, 48}, 20));
  BusNode node("test", "memq://");
  Received r;
  listen(node, r);
  o.loop = true;
  o.duration_s = 2.5;  // 25 frames at 10 fps: two and a half passes
  EXPECT_EQ(run_capture(Config{}, o, node), 0);
  drain(node);
  ASSERT_EQ(r.frames.size(), 25u);
  EXPECT_EQ(r.frames.back().seq, 24);
  for (size_t i = 1; i < r.frames.size(); ++i) {
    EXPECT_GT(r.frames[i].utime, r.frames[i - 1].utime);  // across the loop too
  }
  cv::Mat f;
  ASSERT_EQ(image_to_mat(r.frames[12], f), "");  // frame 2 of the second pass
  EXPECT_NEAR(cv::mean(f)[0], 40.0, 4.0);
}

TEST_F(CaptureService, MissingVideoIsAClearErrorInHealth) {
  BusNode node("test", "memq://");
  Received r;
  listen(node, r);
  EXPECT_EQ(run_capture(Config{}, video((dir_ / "nope.mp4").string()), node), 1);
  drain(node);
  EXPECT_TRUE(r.frames.empty());
  ASSERT_FALSE(r.health.empty());
  EXPECT_EQ(r.health.back().state, health_t::STATE_ERROR);
  EXPECT_NE(r.health.back().state_detail.find("nope.mp4' does not exist"), std::string::npos) << r.health.back().state_detail;
}

TEST_F(CaptureService, ImageFolderInNameOrderWithABadImageRejected) {
  // GIVEN b.png, a.png (grey) and a broken c.jpg
  cv::imwrite((dir_ / "b.png").string(), cv::Mat(48, 64, CV_8UC3, cv::Scalar(0, 0, 200)));
  cv::imwrite((dir_ / "a.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(100)));
  std::ofstream(dir_ / "c.jpg") << "not a jpeg";
  std::ofstream(dir_ / "notes.txt") << "ignored";
  BusNode node("test", "memq://");
  Received r;
  listen(node, r);
  CaptureOptions o;
  o.kind = CaptureOptions::Kind::Images;
  o.source = dir_.string();
  o.as_fast_as_possible = true;
  EXPECT_EQ(run_capture(raw_frames(), o, node), 0);
  drain(node);
  // THEN a.png then b.png (grey became BGR), in time order; c.jpg rejected and counted
  ASSERT_EQ(r.frames.size(), 2u);
  cv::Mat a, b;
  ASSERT_EQ(image_to_mat(r.frames[0], a), "");
  ASSERT_EQ(image_to_mat(r.frames[1], b), "");
  EXPECT_EQ(a.at<cv::Vec3b>(0, 0), cv::Vec3b(100, 100, 100));
  EXPECT_EQ(b.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 200));
  EXPECT_GT(r.frames[1].utime, r.frames[0].utime);
  EXPECT_EQ(node.stats().rejected_count(), 1);
}

TEST_F(CaptureService, SyntheticPublishesTruthWithItsFrameAndFliesWithTheVehicle) {
  BusNode node("test", "memq://");
  Received r;
  listen(node, r);
  // GIVEN the vehicle 1 m closer to the person than the scenario's camera, yawed a little
  vehicle_state_t v{};
  v.position[0] = 1.0f;
  v.position[2] = -1.5f;
  v.attitude[2] = 0.05f;
  v.source = vehicle_state_t::SOURCE_SIMULATOR;
  // (sent when the first frame is seen: memq:// delivers only to channels already subscribed)
  node.subscribe<image_t>("CAMERA", [&node, v](const image_t& m, int64_t) {
    if (m.seq == 0) node.publish("VEHICLE_STATE", v);
  });
  CaptureOptions o;
  o.source = "tour";
  o.as_fast_as_possible = true;
  o.duration_s = 0.4;  // 10 frames at 25 fps
  EXPECT_EQ(run_capture(Config{}, o, node), 0);
  drain(node);
  ASSERT_EQ(r.frames.size(), 10u);
  ASSERT_EQ(r.truths.size(), 10u);
  for (size_t i = 0; i < r.frames.size(); ++i) {
    EXPECT_EQ(r.truths[i].seq, r.frames[i].seq);
    EXPECT_EQ(r.truths[i].utime, r.frames[i].utime);
    EXPECT_EQ(r.frames[i].width, 640);
  }
  // frame 0 is the scenario's camera; after the vehicle state arrived the camera is the vehicle's
  EXPECT_FLOAT_EQ(r.truths[0].camera_position[0], 0.0f);
  EXPECT_FLOAT_EQ(r.truths.back().camera_position[0], 1.0f);
  EXPECT_FLOAT_EQ(r.truths.back().camera_yaw, 0.05f);
  EXPECT_GT(r.truths.back().face_box[2], 1.4f * r.truths[0].face_box[2]);  // 3 m -> 2 m: 1.5x larger
}

TEST_F(CaptureService, JpegByConfig) {
  BusNode node("test", "memq://");
  Received r;
  listen(node, r);
  Config c;
  c.set("capture.pixel_format=JPEG");
  c.set("capture.jpeg_quality=80");
  CaptureOptions o;
  o.as_fast_as_possible = true;
  o.duration_s = 0.08;  // 2 frames
  EXPECT_EQ(run_capture(c, o, node), 0);
  drain(node);
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].pixel_format, image_t::PIXEL_FORMAT_JPEG);
  EXPECT_LT(r.frames[0].size, 640 * 480);  // compressed
  cv::Mat f;
  ASSERT_EQ(image_to_mat(r.frames[0], f), "");
  EXPECT_EQ(f.size(), cv::Size(640, 480));
}

// Issue 14: an MJPEG video's frames are JPEGs already. GIVEN a 20-frame MJPG clip WHEN captured as JPEG (the
// default) THEN each CAMERA message carries the file's own JPEG, byte for byte as FFmpeg stores it (no decode and
// re-encode), with its size read from its header; and it decodes to the frame's content. With
// capture.jpeg_passthrough false, or as BGR8, the frames are decoded and (for JPEG) encoded again.
TEST_F(CaptureService, AnMjpegVideosOwnJpegFramesArePublishedAsStored) {
  const std::string path = write_clip("mjpeg.avi", 20, 20.0, {320, 240}, 10);
  std::vector<std::vector<uint8_t>> stored;
  {
    cv::VideoCapture raw(path, cv::CAP_FFMPEG);
    ASSERT_TRUE(raw.set(cv::CAP_PROP_FORMAT, -1));
    for (cv::Mat packet; raw.read(packet) && !packet.empty();)
      stored.emplace_back(packet.data, packet.data + packet.total() * packet.elemSize());
  }
  ASSERT_EQ(stored.size(), 20u);
  ASSERT_GE(stored[0].size(), 2u);
  EXPECT_EQ(stored[0][0], 0xFF);
  EXPECT_EQ(stored[0][1], 0xD8);  // SOI: each packet is a whole JPEG
  const auto capture = [&](const std::string& yaml) {
    BusNode node("test", "memq://");
    Received r;
    listen(node, r);
    EXPECT_EQ(run_capture(Config::from_string(yaml), video(path), node), 0);
    drain(node);
    return r;
  };
  const Received passed = capture("capture:\n  pixel_format: JPEG\n");
  ASSERT_EQ(passed.frames.size(), 20u);
  for (size_t i = 0; i < passed.frames.size(); ++i) {
    const image_t& m = passed.frames[i];
    EXPECT_EQ(m.pixel_format, image_t::PIXEL_FORMAT_JPEG);
    EXPECT_EQ(m.width, 320);
    EXPECT_EQ(m.height, 240);
    EXPECT_EQ(m.data, stored[i]) << "frame " << i << " was not the file's own JPEG";
    cv::Mat f;
    ASSERT_EQ(image_to_mat(m, f), "");
    EXPECT_NEAR(cv::mean(f)[0], i * 10.0, 3.0);
  }
  ASSERT_FALSE(passed.health.empty());
  const Received encoded = capture("capture:\n  pixel_format: JPEG\n  jpeg_passthrough: false\n");
  ASSERT_EQ(encoded.frames.size(), 20u);
  EXPECT_NE(encoded.frames[5].data, stored[5]);  // decoded, then encoded at capture.jpeg_quality
  const Received raw = capture("capture:\n  pixel_format: BGR8\n");
  ASSERT_EQ(raw.frames.size(), 20u);
  EXPECT_EQ(raw.frames[5].pixel_format, image_t::PIXEL_FORMAT_BGR8);
}

TEST(JpegToImage, RefusesBytesThatAreNoJpegTheStagesCouldDecode) {
  image_t m;
  const std::vector<uint8_t> junk(100, 0x42);
  EXPECT_NE(jpeg_to_image(junk.data(), junk.size(), 1, 2, m), "");
  std::vector<uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 200, 30)), jpeg));
  EXPECT_NE(jpeg_to_image(jpeg.data(), 20, 1, 2, m), "");  // cut before its frame header
  ASSERT_EQ(jpeg_to_image(jpeg.data(), jpeg.size(), 1, 2, m), "");
  EXPECT_EQ(m.utime, 1);
  EXPECT_EQ(m.seq, 2);
  EXPECT_EQ(m.width, 64);
  EXPECT_EQ(m.height, 48);
  EXPECT_EQ(m.size, static_cast<int32_t>(jpeg.size()));
  EXPECT_EQ(m.data, jpeg);
  cv::Mat f;
  ASSERT_EQ(image_to_mat(m, f), "");
  EXPECT_NEAR(cv::mean(f)[1], 200, 3);
}

TEST_F(CaptureService, BadPixelFormatIsAConfigError) {
  BusNode node("test", "memq://");
  Config c;
  c.set("capture.pixel_format=RGB565");
  EXPECT_THROW(run_capture(c, CaptureOptions{}, node), ConfigError);
}

}  // namespace
}  // namespace gpilot
