// Helpers shared by the tests of gpilot-view and gpilot-report: a scratch folder per test, running a
// tool and collecting its output, and (NETNS tests) publishing a synthetic frame and waiting on the bus.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <lcm/lcm-cpp.hpp>

#include "synthetic_run.hpp"

namespace gpilot::test {

// An empty folder named after prefix, the process and the running test; removed by the destructor.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix);
  ~ScratchDir();
  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int code;  // exit status, -1 if it did not exit normally
  std::string out, err;
};
// Runs "program args" through the shell with no DISPLAY; stdout and stderr go through files in dir.
CommandResult run_tool(const std::string& program, const std::string& args, const ScratchDir& dir);

// Handles LCM until done() holds or timeout_s of wall time pass; false on timeout.
bool wait_for(lcm::LCM& lc, double timeout_s, const std::function<bool()>& done);

// Publishes frame seq of run on frames (the frames' URL, bus.frames_url) and its per-frame messages
// (GROUND_TRUTH, USER_TRACK, HAND_OBS, GESTURE_CMD) and VEHICLE_STATE on lc (the bus).
void publish_frame(lcm::LCM& lc, lcm::LCM& frames, const SyntheticRun& run, int64_t seq);

}  // namespace gpilot::test
