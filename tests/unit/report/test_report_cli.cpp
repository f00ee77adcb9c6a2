// gpilot-report as a program: files written, table and --json on stdout, config respected, bad logs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "json_out.hpp"
#include "tool_test_helpers.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;
const std::string kReport = std::string(GPILOT_BIN_DIR) + "/gpilot-report";

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class ReportCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    log = dir / "log.lcmlog";
    run.size = cv::Size(32, 24);
    test::write_synthetic_log(log, run);
  }
  test::CommandResult report(const std::string& args) { return test::run_tool(kReport, args, dir); }
  test::ScratchDir dir{"gpilot_report_cli"};
  std::string log;
  test::SyntheticRun run;
};

TEST_F(ReportCliTest, WritesSummaryAndPlotAndPrintsATable) {
  const test::CommandResult r = report(log + " --out " + dir / "run");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("gesture accuracy  60.0 %"), std::string::npos) << r.out;
  const std::string text = slurp(dir / "run/summary.json");
  const json j = json::parse(text);
  EXPECT_EQ(j["gesture_accuracy"]["accuracy"], 0.6) << text;  // 36 of 60: judged from 0.8 s after each change
  EXPECT_EQ(j["frames"], 100);
  EXPECT_EQ(j["latency_ms"]["frame_to_gesture_cmd"], json({{"n", 100}, {"median", 74}, {"p95", 79}})) << text;
  // One member a line: deploy/run reads logger_lost with a line-wise sed.
  EXPECT_NE(text.find("\n    \"logger_lost\": 0,\n"), std::string::npos) << text;
  const cv::Mat png = cv::imread(dir / "run/trajectory.png");
  ASSERT_FALSE(png.empty());
  EXPECT_GE(png.cols, 1000);
}

TEST_F(ReportCliTest, JsonOnStdoutAndTheBufferSizeFromConfig) {
  const test::CommandResult r = report(log + " --json --set decide.rule=paper --set decide.buffer_size=20 --set decide.out_threshold=10 --set decide.front_threshold=10");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);  // one object, nothing else on stdout
  EXPECT_EQ(j["buffer_size"], 20);
  EXPECT_EQ(j["gesture_accuracy"]["settle_frames"], 11) << r.out;
  EXPECT_EQ(j["gesture_accuracy"]["correct"], 36) << r.out;
  EXPECT_EQ(j["gesture_accuracy"]["evaluated"], 78) << r.out;
  EXPECT_EQ(report(log + " --json --set decide.buffer_size=-3").code, 2);
  // The evidence rule (the default) is judged from 0.8 s after each change: 20 frames at 25 Hz.
  const test::CommandResult e = report(log + " --json");
  ASSERT_EQ(e.code, 0) << e.err;
  const json je = json::parse(e.out);
  EXPECT_EQ(je["decide_rule"], "evidence");
  EXPECT_EQ(je["gesture_accuracy"]["settle_s"], 0.8) << e.out;
  EXPECT_EQ(je["gesture_accuracy"]["evaluated"], 60) << e.out;
}

TEST_F(ReportCliTest, ATruncatedLogIsReportedWithAWarning) {
  fs::resize_file(log, fs::file_size(log) - 10);
  const test::CommandResult r = report(log + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  const json warnings = json::parse(r.out)["warnings"];
  ASSERT_EQ(warnings.size(), 1u) << r.out;
  EXPECT_EQ(warnings[0].get<std::string>().rfind("log truncated", 0), 0u) << r.out;
}

TEST_F(ReportCliTest, MissingOrForeignLogsAreErrors) {
  test::CommandResult r = report(dir / "nope.lcmlog");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("No such file"), std::string::npos) << r.err;
  std::ofstream(dir / "text.lcmlog") << "not a log\n";
  r = report(dir / "text.lcmlog");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("not an LCM log"), std::string::npos) << r.err;
  EXPECT_NE(report("").code, 0);  // LOG is required
}

}  // namespace
}  // namespace gpilot
