// gpilot-synth-sheet as a program: one PNG with a tile per key pose; a scenario that does not exist is an
// error with a non-zero status and no PNG.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

namespace {

namespace fs = std::filesystem;

int run(const std::string& args) {
  const int status = std::system((std::string(GPILOT_BIN_DIR) + "/gpilot-synth-sheet " + args + " 2>/dev/null >/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SynthSheetCli, OneTilePerKeyPose) {
  const fs::path out = fs::temp_directory_path() / ("gpilot-sheet-" + std::to_string(getpid()) + ".png");
  // idle has 4 keyframes: one row of 4 tiles, 200 px high
  ASSERT_EQ(run("idle --tile-height 200 --columns 5 --out " + out.string()), 0);
  const cv::Mat sheet = cv::imread(out.string());
  ASSERT_FALSE(sheet.empty());
  EXPECT_EQ(sheet.rows, 200);
  EXPECT_GT(sheet.cols, 4 * 150);
  EXPECT_LT(sheet.cols, 4 * 400);
  fs::remove(out);
}

TEST(SynthSheetCli, MissingScenarioIsAnError) {
  const fs::path out = fs::temp_directory_path() / ("gpilot-sheet-missing-" + std::to_string(getpid()) + ".png");
  EXPECT_NE(run("no-such-scenario --out " + out.string()), 0);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
