// gpilot-view as a program on a synthetic log: the MP4 reads back with every frame, the PNGs show the
// red marks on the frame they belong to, bad logs and bad arguments give clear errors.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "synthetic_run.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;
const std::string kView = std::string(GPILOT_BIN_DIR) + "/gpilot-view";

struct Result {
  int code;
  std::string output;
};

Result run_cmd(const std::string& args, const fs::path& dir) {
  const std::string out = (dir / "output.txt").string();
  const int status = std::system(("env -u DISPLAY " + kView + " " + args + " > " + out + " 2>&1").c_str());
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
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
    dir = fs::temp_directory_path() /
          ("gpilot_view_cli_" + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
    log = (dir / "run.lcmlog").string();
    run.frames = 12;
    run.decided_mode = [](int64_t) { return gesture_cmd_t::MODE_FINE; };
    test::write_synthetic_log(log, run);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path dir;
  std::string log;
  test::SyntheticRun run;
};

TEST_F(ViewCliTest, LogToMp4AndPngsWithMarksOnTheRightFrame) {
  const std::string mp4 = (dir / "annotated.mp4").string();
  const Result r = run_cmd("--log " + log + " --headless --video " + mp4 + " --png-every 5 " + (dir / "png").string(), dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(count_frames(mp4), 12) << r.output;
  // Frames 0, 5 and 10 as PNG; in each, the red box is this frame's (the box moves 4 px a frame, and the
  // messages of a frame reach the log up to two frames after it).
  for (int seq : {0, 5, 10}) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", seq);
    const std::string png = (dir / "png" / name).string();
    const cv::Mat img = cv::imread(png);
    ASSERT_FALSE(img.empty()) << png << "\n" << r.output;
    EXPECT_GT(img.rows, run.size.height);  // HUD strip
    const int x = static_cast<int>(test::user_box_of(seq).x);
    EXPECT_TRUE(is_red(img, x, 150)) << "seq " << seq;
    EXPECT_FALSE(is_red(img, x - 4, 150)) << "seq " << seq << ": previous frame's box";
    EXPECT_FALSE(is_red(img, x + 4, 150)) << "seq " << seq << ": next frame's box";
    const cv::Point2f uc = test::shoulder_centre_of(seq);
    EXPECT_TRUE(is_red(img, cvRound(uc.x), cvRound(uc.y))) << "seq " << seq << ": command mark at p_uc";
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "png"), fs::directory_iterator{}), 3);
}

TEST_F(ViewCliTest, TruncatedLogStillGivesAPlayableVideoAndAWarning) {
  const auto size = fs::file_size(log);
  fs::resize_file(log, size - 1000);
  const std::string mp4 = (dir / "cut.mp4").string();
  const Result r = run_cmd("--log " + log + " --headless --video " + mp4, dir);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  const int n = count_frames(mp4);
  EXPECT_GE(n, 10);
  EXPECT_LE(n, 12);
}

TEST_F(ViewCliTest, ClearErrors) {
  Result r = run_cmd("--log " + (dir / "missing.lcmlog").string() + " --headless --video x.mp4", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("No such file"), std::string::npos) << r.output;
  r = run_cmd("--log " + log + " --headless", dir);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("nothing to do"), std::string::npos) << r.output;
  r = run_cmd("--log " + log + " --png-every 0 " + dir.string(), dir);
  EXPECT_NE(r.code, 0);
  r = run_cmd("--help", dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("--video"), std::string::npos);
}

}  // namespace
}  // namespace gpilot
