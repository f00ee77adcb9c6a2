#include "tool_test_helpers.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "clock.hpp"

namespace gpilot::test {

namespace fs = std::filesystem;

ScratchDir::ScratchDir(const std::string& prefix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  path_ = fs::temp_directory_path() /
          (prefix + "_" + std::to_string(::getpid()) + "_" + (info ? std::string(info->name()) : std::string("x")));
  fs::remove_all(path_);
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

namespace {
std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

CommandResult run_tool(const std::string& program, const std::string& args, const ScratchDir& dir) {
  const std::string out = dir / "tool_stdout.txt", err = dir / "tool_stderr.txt";
  const int status = std::system(("env -u DISPLAY " + program + " " + args + " > " + out + " 2> " + err).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

bool wait_for(lcm::LCM& lc, double timeout_s, const std::function<bool()>& done) {
  const int64_t end = monotonic_utime() + seconds_to_utime(timeout_s);
  while (!done()) {
    if (monotonic_utime() > end) return false;
    lc.handleTimeout(50);
  }
  return true;
}

void publish_frame(lcm::LCM& lc, lcm::LCM& frames, const SyntheticRun& run, int64_t s) {
  const image_t img = camera_of(run, s);
  frames.publish("CAMERA", &img);
  const auto truth = truth_of(run, s);
  lc.publish("GROUND_TRUTH", &truth);
  const auto track = track_of(run, s);
  lc.publish("USER_TRACK", &track);
  const auto hand = hand_of(run, s);
  lc.publish("HAND_OBS", &hand);
  const auto cmd = cmd_of(run, s);
  lc.publish("GESTURE_CMD", &cmd);
  const auto vehicle = vehicle_of(run, s);
  lc.publish("VEHICLE_STATE", &vehicle);
}

}  // namespace gpilot::test
