// gpilot-eval-decide as a program: --json is one JSON object on stdout with the keys and digits readers use,
// the reading of each log is an info line of common/log.hpp on stderr.
#include <gtest/gtest.h>

#include "json_out.hpp"
#include "tool_test_helpers.hpp"

namespace gpilot {
namespace {

const std::string kEvalDecide = std::string(GPILOT_BIN_DIR) + "/gpilot-eval-decide";

// GIVEN the synthetic run (100 frames; GROUND_TRUTH says REST throughout, its GESTURE_CMD are motions on 69
// frames in 6 episodes: see tests/unit/report) WHEN evaluated with --json THEN the recorded row scores those
// commands as gpilot-report does, the paper's configuration and the given one follow, and strings are escaped.
TEST(EvalDecideCli, JsonIsOneObjectWithTheRecordedRunFirst) {
  const test::ScratchDir dir("gpilot_eval_decide_cli");
  test::SyntheticRun run;
  run.size = cv::Size(32, 24);
  const std::string log = dir / "run \"1\".lcmlog";  // a quote in the name: escaped in the JSON
  test::write_synthetic_log(log, run);
  const test::CommandResult r = test::run_tool(kEvalDecide, "'" + log + "' --json", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);  // nothing else on stdout
  EXPECT_EQ(j["logs"], json::array({log}));
  EXPECT_EQ(j["rules"], json({{"turn_deg", 30.0}, {"fine_angle_deg", 30.0}, {"min_turn_s", 1.0}})) << r.out;
  ASSERT_EQ(j["configurations"].size(), 3u) << r.out;  // recorded, paper, the config as given
  const json& recorded = j["configurations"][0];
  EXPECT_EQ(recorded["name"], "recorded (live run)");
  EXPECT_EQ(recorded["sets"], json::array());
  const json& g = recorded["gesture_cmd"];
  EXPECT_EQ(g["frames"], 100);
  EXPECT_EQ(g["minutes"], 0.066) << r.out;  // 3.96 s from the first frame to the last, three decimals
  EXPECT_EQ(g["changes"], 0);
  EXPECT_TRUE(g["reaction_median_s"].is_null()) << r.out;  // no change to react to
  EXPECT_EQ(g["false_at_rest"], 3);  // the commands equal to the frame's expected mode are not false
  EXPECT_EQ(g["false_at_rest_frames"], 33);
  EXPECT_EQ(g["wrong_percent"], 69.0);
  EXPECT_EQ(g["false_per_minute"], 45.455) << r.out;  // 3 / (3.96 s / 60)
  ASSERT_EQ(recorded["per_log"].size(), 1u);
  EXPECT_EQ(recorded["per_log"][0]["log"], log);
  EXPECT_EQ(recorded["per_log"][0]["gesture_cmd"], g);
  EXPECT_EQ(j["configurations"][1]["name"], "paper");
  EXPECT_EQ(j["configurations"][2]["name"], "config");
  EXPECT_NE(r.err.find("gpilot-eval-decide: info: reading " + log), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gpilot
