// gpilot-view live and headless over real LCM (inside the test's network namespace): frames and their
// messages are published, the viewer writes the MP4 until SIGTERM, and the file reads back whole.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>
#include <opencv2/videoio.hpp>

#include "bus_node.hpp"
#include "clock.hpp"
#include "synthetic_run.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;
const std::string kView = std::string(GPILOT_BIN_DIR) + "/gpilot-view";

struct ViewHealth {
  bool seen = false;
  std::string detail;
  static void on(const lcm::ReceiveBuffer*, const std::string&, const health_t* m, ViewHealth* self) {
    if (m->name != "gpilot-view") return;
    self->seen = true;
    self->detail = m->state_detail;
  }
};

// Handles LCM until done() or timeout_s of wall time.
template <class Done>
bool wait_for(lcm::LCM& lc, double timeout_s, Done done) {
  const int64_t end = monotonic_utime() + seconds_to_utime(timeout_s);
  while (!done()) {
    if (monotonic_utime() > end) return false;
    lc.handleTimeout(50);
  }
  return true;
}

TEST(ViewLive, HeadlessWritesAPlayableMp4UntilSigterm) {
  const fs::path dir = fs::temp_directory_path() / ("gpilot_view_live_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string mp4 = (dir / "annotated.mp4").string();
  const std::string url = kDefaultLcmUrl;
  lcm::LCM lc(url);
  ASSERT_TRUE(lc.good()) << "no multicast route in this namespace";
  ViewHealth health;
  lc.subscribeFunction("HEALTH", &ViewHealth::on, &health);

  // GIVEN gpilot-view running headless on the bus
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string log = (dir / "view.txt").string();
    if (!freopen(log.c_str(), "w", stderr)) _exit(126);
    execl(kView.c_str(), kView.c_str(), "--lcm-url", url.c_str(), "--headless", "--video", mp4.c_str(), "--fps", "25",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_TRUE(wait_for(lc, 20.0, [&] { return health.seen; })) << "gpilot-view never reported HEALTH";

  // WHEN 20 frames with their per-frame messages are published
  test::SyntheticRun run;
  run.size = cv::Size(160, 120);
  run.decided_mode = [](int64_t) { return gesture_cmd_t::MODE_FINE; };
  const int kFrames = 20;
  for (int s = 0; s < kFrames; ++s) {
    const image_t img = test::camera_of(run, s);
    lc.publish("CAMERA", &img);
    const auto truth = test::truth_of(run, s);
    lc.publish("GROUND_TRUTH", &truth);
    const auto track = test::track_of(run, s);
    lc.publish("USER_TRACK", &track);
    const auto hand = test::hand_of(run, s);
    lc.publish("HAND_OBS", &hand);
    const auto cmd = test::cmd_of(run, s);
    lc.publish("GESTURE_CMD", &cmd);
    const auto vehicle = test::vehicle_of(run, s);
    lc.publish("VEHICLE_STATE", &vehicle);
    lc.handleTimeout(20);
  }
  const bool all_in = wait_for(lc, 20.0, [&] {
    return health.detail.find("received " + std::to_string(kFrames) + " frames") != std::string::npos;
  });

  // THEN after SIGTERM it exits cleanly and the MP4 has every frame
  kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(all_in) << "last HEALTH detail: " << health.detail;
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  cv::VideoCapture cap(mp4, cv::CAP_FFMPEG);
  ASSERT_TRUE(cap.isOpened()) << mp4;
  int n = 0;
  cv::Mat f, frame5;
  while (cap.read(f)) {
    if (n == 5) frame5 = f.clone();
    ++n;
  }
  EXPECT_EQ(n, kFrames);
  ASSERT_FALSE(frame5.empty());
  // The red box edge of frame 5 survives the encoding as clearly red.
  const cv::Vec3b edge = frame5.at<cv::Vec3b>(100, static_cast<int>(test::user_box_of(5).x));
  EXPECT_GT(edge[2] - edge[1], 60) << edge;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gpilot
