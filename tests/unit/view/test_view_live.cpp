// gpilot-view live and headless over real LCM (inside the test's network namespace): frames and their
// messages are published, the viewer writes the MP4 until SIGTERM, and the file reads back whole.
#include <gtest/gtest.h>

#include <csignal>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>
#include <opencv2/videoio.hpp>

#include "bus_node.hpp"
#include "clock.hpp"
#include "tool_test_helpers.hpp"

namespace gpilot {
namespace {

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

TEST(ViewLive, HeadlessWritesAPlayableMp4UntilSigterm) {
  const test::ScratchDir dir("gpilot_view_live");
  const std::string mp4 = dir / "annotated.mp4";
  const std::string url = kDefaultLcmUrl;
  lcm::LCM lc(url);
  ASSERT_TRUE(lc.good()) << "no multicast route in this namespace";
  lcm::LCM frames(frames_url_for(url, BusParams{}));  // CAMERA travels on the frames' URL
  ASSERT_TRUE(frames.good());
  ViewHealth health;
  lc.subscribeFunction("HEALTH", &ViewHealth::on, &health);

  // GIVEN gpilot-view running headless on the bus
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string log = dir / "view.txt";
    if (!freopen(log.c_str(), "w", stderr)) _exit(126);
    execl(kView.c_str(), kView.c_str(), "--lcm-url", url.c_str(), "--headless", "--video", mp4.c_str(), "--fps", "25",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_TRUE(test::wait_for(lc, 20.0, [&] { return health.seen; })) << "gpilot-view never reported HEALTH";

  // WHEN 20 frames with their per-frame messages are published
  test::SyntheticRun run;
  run.t0 = wall_utime();  // the bus rejects messages whose utime is far from their arrival
  run.size = cv::Size(160, 120);
  run.decided_mode = [](int64_t) { return gesture_cmd_t::MODE_FINE; };
  const int kFrames = 20;
  for (int s = 0; s < kFrames; ++s) {
    test::publish_frame(lc, frames, run, s);
    lc.handleTimeout(20);
  }
  const bool all_in = test::wait_for(lc, 20.0, [&] {
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
}

}  // namespace
}  // namespace gpilot
