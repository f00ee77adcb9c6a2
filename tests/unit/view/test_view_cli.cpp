// gpilot-view as a program on a synthetic log: the MP4 reads back with every frame, the PNGs show the
// red marks on the frame they belong to, bad logs and bad arguments give clear errors.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "tool_test_helpers.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;
const std::string kView = std::string(GPILOT_BIN_DIR) + "/gpilot-view";

test::CommandResult run_cmd(const std::string& args, const test::ScratchDir& dir) {
  return test::run_tool(kView, args, dir);
}

int count_frames(const std::string& mp4) {
  cv::VideoCapture cap(mp4, cv::CAP_FFMPEG);
  if (!cap.isOpened()) return -1;
  int n = 0;
  cv::Mat f;
  while (cap.read(f)) ++n;
  return n;
}

bool is_red(const cv::Mat& img, int x, int y) { return img.at<cv::Vec3b>(y, x) == cv::Vec3b(0, 0, 255); }

class ViewCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    log = dir / "run.lcmlog";
    run.frames = 12;
    run.decided_mode = [](int64_t) { return gesture_cmd_t::MODE_FINE; };
    test::write_synthetic_log(log, run);
  }
  test::ScratchDir dir{"gpilot_view_cli"};
  std::string log;
  test::SyntheticRun run;
};

TEST_F(ViewCliTest, LogToMp4AndPngsWithMarksOnTheRightFrame) {
  const std::string mp4 = dir / "annotated.mp4";
  const test::CommandResult r = run_cmd("--log " + log + " --headless --video " + mp4 + " --png-every 5 " + dir / "png", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(count_frames(mp4), 12) << r.err;
  // Frames 0, 5 and 10 as PNG; in each, the red box is this frame's (the box moves 4 px a frame, and the
  // messages of a frame reach the log up to two frames after it).
  for (int seq : {0, 5, 10}) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", seq);
    const std::string png = (dir.path() / "png" / name).string();
    const cv::Mat img = cv::imread(png);
    ASSERT_FALSE(img.empty()) << png << "\n" << r.err;
    EXPECT_GT(img.rows, run.size.height);  // HUD strip
    const int x = static_cast<int>(test::user_box_of(seq).x);
    EXPECT_TRUE(is_red(img, x, 150)) << "seq " << seq;
    EXPECT_FALSE(is_red(img, x - 4, 150)) << "seq " << seq << ": previous frame's box";
    EXPECT_FALSE(is_red(img, x + 4, 150)) << "seq " << seq << ": next frame's box";
    const cv::Point2f uc = test::shoulder_centre_of(seq);
    EXPECT_TRUE(is_red(img, cvRound(uc.x), cvRound(uc.y))) << "seq " << seq << ": command mark at p_uc";
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path() / "png"), fs::directory_iterator{}), 3);
}

TEST_F(ViewCliTest, TruncatedLogStillGivesAPlayableVideoAndAWarning) {
  const auto size = fs::file_size(log);
  fs::resize_file(log, size - 1000);
  const std::string mp4 = dir / "cut.mp4";
  const test::CommandResult r = run_cmd("--log " + log + " --headless --video " + mp4, dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  const int n = count_frames(mp4);
  EXPECT_GE(n, 10);
  EXPECT_LE(n, 12);
}

TEST_F(ViewCliTest, ClearErrors) {
  test::CommandResult r = run_cmd("--log " + dir / "missing.lcmlog" + " --headless --video x.mp4", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("No such file"), std::string::npos) << r.err;
  r = run_cmd("--log " + log + " --headless", dir);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("nothing to do"), std::string::npos) << r.err;
  r = run_cmd("--log " + log + " --png-every 0 " + dir.path().string(), dir);
  EXPECT_NE(r.code, 0);
  r = run_cmd("--help", dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--video"), std::string::npos);
}

}  // namespace
}  // namespace gpilot
