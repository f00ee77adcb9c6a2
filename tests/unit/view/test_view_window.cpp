// gpilot-view's window under Xvfb, inside the test's network namespace: dragging a box sends
// TRACKER_INIT SET_BOX with that box in image pixels, 'r' sends RESET, 'e' FLIGHT_CONTROL ENGAGE.
// Skipped where Xvfb or xdotool is not installed (deploy/setup installs both).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <poll.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>

#include "bus_node.hpp"
#include "clock.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "tool_test_helpers.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;
const std::string kView = std::string(GPILOT_BIN_DIR) + "/gpilot-view";

struct Heard {
  std::string view_detail;
  std::vector<tracker_init_t> inits;
  std::vector<flight_control_t> controls;
  static void health(const lcm::ReceiveBuffer*, const std::string&, const health_t* m, Heard* h) {
    if (m->name == "gpilot-view") h->view_detail = m->state_detail.empty() ? "up" : m->state_detail;
  }
  static void init(const lcm::ReceiveBuffer*, const std::string&, const tracker_init_t* m, Heard* h) { h->inits.push_back(*m); }
  static void control(const lcm::ReceiveBuffer*, const std::string&, const flight_control_t* m, Heard* h) {
    h->controls.push_back(*m);
  }
};

pid_t spawn(const std::vector<std::string>& argv, const std::string& log) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  if (!freopen(log.c_str(), "w", stderr)) _exit(126);
  if (!freopen("/dev/null", "w", stdout)) _exit(126);
  std::vector<char*> a;
  for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
  a.push_back(nullptr);
  execv(a[0], a.data());
  _exit(127);
}

// Starts Xvfb on a display it chooses itself (-displayfd: the first free one, written to a pipe once the server
// accepts connections), so parallel tests never pick the same display. Returns the display (":N"), or "" when
// Xvfb said nothing within 10 s.
std::string start_xvfb(const std::string& log, pid_t& pid) {
  int fds[2];
  if (pipe(fds) != 0) return "";
  pid = fork();
  if (pid == 0) {
    close(fds[0]);
    if (!freopen(log.c_str(), "w", stderr)) _exit(126);
    if (!freopen("/dev/null", "w", stdout)) _exit(126);
    const std::string fd = std::to_string(fds[1]);
    execl("/usr/bin/Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "800x600x24", "-nolisten", "tcp",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  std::string number;
  pollfd p{fds[0], POLLIN, 0};
  char c = 0;
  while (poll(&p, 1, 10000) > 0 && read(fds[0], &c, 1) == 1 && c != '\n') number += c;
  close(fds[0]);
  return number.empty() ? "" : ":" + number;
}

void stop(pid_t pid) {
  if (pid <= 0) return;
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
}

TEST(ViewWindow, DragSendsTheBoxAndKeysSendCommands) {
  if (access("/usr/bin/Xvfb", X_OK) != 0 || access("/usr/bin/xdotool", X_OK) != 0)
    GTEST_SKIP() << "Xvfb or xdotool not installed (deploy/setup installs them)";
  const test::ScratchDir dir("gpilot_view_window");
  pid_t xvfb = -1;
  const std::string display = start_xvfb(dir / "xvfb.txt", xvfb);
  if (display.empty()) stop(xvfb);
  ASSERT_FALSE(display.empty()) << "Xvfb did not start (see its output in " << dir / "xvfb.txt" << ")";
  setenv("DISPLAY", display.c_str(), 1);

  lcm::LCM lc(kDefaultLcmUrl);
  ASSERT_TRUE(lc.good());
  lcm::LCM frames(frames_url_for(kDefaultLcmUrl, BusParams{}));  // CAMERA travels on the frames' URL
  ASSERT_TRUE(frames.good());
  Heard heard;
  lc.subscribeFunction("HEALTH", &Heard::health, &heard);
  lc.subscribeFunction("TRACKER_INIT", &Heard::init, &heard);
  lc.subscribeFunction("FLIGHT_CONTROL", &Heard::control, &heard);
  const pid_t view = spawn({kView, "--lcm-url", kDefaultLcmUrl}, dir / "view.txt");
  ASSERT_TRUE(test::wait_for(lc, 20.0, [&] { return !heard.view_detail.empty(); })) << "no HEALTH from gpilot-view";

  // GIVEN the window showing frames
  test::SyntheticRun run;
  run.size = cv::Size(320, 240);
  run.t0 = wall_utime();  // frames stamped now: the bus refuses a utime outside bus.time_window_s of its arrival
  for (int s = 0; s < 20; ++s) {  // more than the viewer's hold (12), so frames are drawn
    const image_t img = test::camera_of(run, s);
    frames.publish("CAMERA", &img);
    lc.handleTimeout(30);
  }
  ASSERT_TRUE(test::wait_for(lc, 20.0, [&] { return heard.view_detail.find("received 20 frames, drew 1") != std::string::npos; }))
      << heard.view_detail;
  const std::string xdo = "DISPLAY=" + display + " /usr/bin/xdotool ";
  const std::string win = "$(" + xdo + "search --sync --onlyvisible --name '^gpilot-view$' | head -1)";

  // WHEN a box is dragged from (40, 30) to (100, 80), then 'r' and 'e' are pressed
  ASSERT_EQ(std::system(("W=" + win + "; " + xdo + "mousemove --window $W 40 30 mousedown 1 mousemove --window $W 70 50 " +
                         "mousemove --window $W 100 80 mouseup 1 && " + xdo + "windowfocus --sync $W && sleep 0.3 && " +
                         xdo + "key --window $W r && sleep 0.2 && " + xdo + "key --window $W e")
                            .c_str()),
            0);

  // THEN the bus hears the box in image pixels, the reset and the engage, each from gpilot-view
  EXPECT_TRUE(test::wait_for(lc, 10.0, [&] { return heard.inits.size() >= 2 && !heard.controls.empty(); }));
  stop(view);
  stop(xvfb);
  ASSERT_GE(heard.inits.size(), 2u);
  EXPECT_EQ(heard.inits[0].command, tracker_init_t::COMMAND_SET_BOX);
  EXPECT_FLOAT_EQ(heard.inits[0].box[0], 40);
  EXPECT_FLOAT_EQ(heard.inits[0].box[1], 30);
  EXPECT_FLOAT_EQ(heard.inits[0].box[2], 60);
  EXPECT_FLOAT_EQ(heard.inits[0].box[3], 50);
  EXPECT_EQ(heard.inits[0].source, "gpilot-view");
  EXPECT_EQ(heard.inits[1].command, tracker_init_t::COMMAND_RESET);
  ASSERT_FALSE(heard.controls.empty());
  EXPECT_EQ(heard.controls[0].command, flight_control_t::COMMAND_ENGAGE);
}

}  // namespace
}  // namespace gpilot
