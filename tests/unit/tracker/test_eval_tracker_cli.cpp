// gpilot-eval-tracker as a program on an OTB-layout folder: each tracker runs over the sequence in a pass of its
// own, and with --repeat its speed is the median of its passes while its boxes (so its scores) are the first's.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tool_test_helpers.hpp"

namespace gpilot {
namespace {

const std::string kEvalTracker = std::string(GPILOT_BIN_DIR) + "/gpilot-eval-tracker";

// A 24-frame OTB folder: a striped 30x50 block gliding 2 px a frame right and 1 down over a noise field, its
// box in groundtruth_rect.txt (1-based x, y).
void write_sequence(const std::string& dir) {
  std::filesystem::create_directories(dir + "/img");
  std::ofstream truth(dir + "/groundtruth_rect.txt");
  cv::Mat field(120, 200, CV_8UC3);
  cv::RNG rng(3);
  rng.fill(field, cv::RNG::UNIFORM, 60, 120);
  for (int i = 0; i < 24; ++i) {
    cv::Mat img = field.clone();
    const cv::Rect box(40 + 2 * i, 30 + i, 30, 50);
    for (int y = 0; y < box.height; ++y)
      img(cv::Rect(box.x, box.y + y, box.width, 1)).setTo(y % 10 < 5 ? cv::Scalar(30, 40, 200) : cv::Scalar(220, 230, 240));
    char name[64];
    std::snprintf(name, sizeof name, "/img/%04d.jpg", i + 1);
    cv::imwrite(dir + name, img);
    truth << box.x + 1 << "," << box.y + 1 << "," << box.width << "," << box.height << "\n";
  }
}

TEST(EvalTrackerCli, EachTrackerInAPassOfItsOwnRepeatedForItsSpeedWithTheFirstPasssBoxes) {
  const test::ScratchDir dir("gpilot_eval_tracker_cli");
  const std::string seq = dir / "glide";
  write_sequence(seq);
  const test::CommandResult once = test::run_tool(kEvalTracker, "'" + seq + "' --json --compare --trace '" + (dir / "once.csv") + "'", dir);
  ASSERT_EQ(once.code, 0) << once.err;
  const test::CommandResult thrice = test::run_tool(kEvalTracker, "'" + seq + "' --json --compare --repeat 3 --trace '" + (dir / "thrice.csv") + "'", dir);
  ASSERT_EQ(thrice.code, 0) << thrice.err;
  const nlohmann::json a = nlohmann::json::parse(once.out), b = nlohmann::json::parse(thrice.out);
  EXPECT_EQ(a["repeat"], 1);
  EXPECT_EQ(b["repeat"], 3);
  EXPECT_EQ(a["frames"], 24);
  ASSERT_GE(a["trackers"].size(), 5u);  // ours, DSST alone, CSRT, KCF, MOSSE (and dlib when built with it)
  ASSERT_EQ(a["trackers"].size(), b["trackers"].size());
  // Ours follows the block (a known answer), and every tracker's boxes are the same in both runs.
  EXPECT_GT(a["success_auc"].get<double>(), 0.6) << once.out;
  for (size_t i = 0; i < a["trackers"].size(); ++i) {
    const auto& x = a["trackers"][i];
    const auto& y = b["trackers"][i];
    EXPECT_EQ(x["name"], y["name"]);
    EXPECT_EQ(x["success_auc"], y["success_auc"]) << x["name"];
    EXPECT_EQ(x["final_box"], y["final_box"]) << x["name"];
    EXPECT_EQ(x["frames_lost"], y["frames_lost"]) << x["name"];
    EXPECT_GT(y["ms_per_frame"].get<double>(), 0.0) << x["name"];
  }
  // The trace is the first pass's, a row a frame after the start: the same in both runs.
  std::ifstream t1(dir / "once.csv"), t3(dir / "thrice.csv");
  const std::string s1((std::istreambuf_iterator<char>(t1)), {}), s3((std::istreambuf_iterator<char>(t3)), {});
  EXPECT_EQ(std::count(s1.begin(), s1.end(), '\n'), 24);  // the header and frames 2..24
  EXPECT_EQ(s1, s3);
  // Progress names the pass.
  EXPECT_NE(thrice.err.find("gpilot UserTracker: pass 3 of 3"), std::string::npos) << thrice.err;
}

// --occlude paints the same pixels for every tracker: the whole frame grey from frame 12 hides the block, and
// every tracker scores lower than on the clear sequence. A spec or texture it cannot use is refused, named.
TEST(EvalTrackerCli, AnOccluderHidesTheTargetFromEveryTrackerABadOneIsRefused) {
  const test::ScratchDir dir("gpilot_eval_tracker_occlude");
  const std::string seq = dir / "glide";
  write_sequence(seq);
  const test::CommandResult clear = test::run_tool(kEvalTracker, "'" + seq + "' --json --compare", dir);
  ASSERT_EQ(clear.code, 0) << clear.err;
  const test::CommandResult hidden = test::run_tool(kEvalTracker, "'" + seq + "' --json --compare --occlude 0,0,200,120@12-", dir);
  ASSERT_EQ(hidden.code, 0) << hidden.err;
  const nlohmann::json a = nlohmann::json::parse(clear.out), b = nlohmann::json::parse(hidden.out);
  EXPECT_EQ(b["sequence"], "glide (occluded)");
  ASSERT_EQ(a["trackers"].size(), b["trackers"].size());
  for (size_t i = 0; i < a["trackers"].size(); ++i)
    EXPECT_LT(b["trackers"][i]["success_auc"].get<double>(), a["trackers"][i]["success_auc"].get<double>() - 0.2)
        << a["trackers"][i]["name"];
  for (const char* bad : {"--occlude 1,2,3", "--occlude 1,2,3,4@0-5", "--occlude 1,2,3,4 --occluder-image /nonexistent.jpg"}) {
    const test::CommandResult r = test::run_tool(kEvalTracker, "'" + seq + "' " + bad, dir);
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.err.find(std::string(bad).find("image") != std::string::npos ? "--occluder-image" : "--occlude"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace gpilot
