// Two hosts, as a drone and its ground station are deployed: two network namespaces joined by a veth pair
// with a multicast route, LCM at ttl=1. Perception and flight run on "drone" (gpilot-launch with
// deploy/services.yaml, no logger and no video there), gpilot-view and lcm-logger on "ground". The ground
// station receives every channel; and at ttl=0 (the default) nothing leaves the drone.
// Run by tests/two-hosts-run (a private mount + network namespace, so the hosts vanish with the test).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "child_process.hpp"
#include "gpilot/health_t.hpp"

namespace fs = std::filesystem;

namespace gpilot {
namespace {

const std::string kUrlTtl1 = "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4194304";
const std::string kUrlTtl0 = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

void sh(const std::string& cmd) { ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd; }

using test::ChildProcess;

struct Heard { std::map<std::string, int> channels; std::map<std::string, int> health; };

Heard read_log(const std::string& path) {
  Heard h;
  lcm::LogFile log(path, "r");
  if (!log.good()) return h;
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev; ev = log.readNextEvent()) {
    ++h.channels[ev->channel];
    if (std::string(ev->channel) == "HEALTH") {
      health_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) ++h.health[m.name];
    }
  }
  return h;
}

class TwoHosts : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::getenv("GPILOT_TWO_HOSTS")) GTEST_SKIP() << "run through tests/two-hosts-run";
    dir_ = fs::temp_directory_path() / ("gpilot-two-hosts-" + std::to_string(getpid()));
    fs::create_directories(dir_);
    sh("ip netns add drone && ip netns add ground && ip link add veth-d type veth peer name veth-g && "
       "ip link set veth-d netns drone && ip link set veth-g netns ground && "
       "ip -n drone addr add 10.77.0.1/24 dev veth-d && ip -n ground addr add 10.77.0.2/24 dev veth-g && "
       "ip -n drone link set lo up && ip -n ground link set lo up && "
       "ip -n drone link set veth-d up && ip -n ground link set veth-g up && "
       "ip -n drone route add 224.0.0.0/4 dev veth-d && ip -n ground route add 224.0.0.0/4 dev veth-g");
  }
  void TearDown() override {
    std::system("ip netns del drone 2>/dev/null; ip netns del ground 2>/dev/null");
    if (!HasFailure() && !dir_.empty()) fs::remove_all(dir_);
  }
  std::string dir_;
};

TEST_F(TwoHosts, GroundStationHearsEveryChannelOfTheDrone) {
  const std::string src = GPILOT_SOURCE_DIR, bin = GPILOT_BIN_DIR;
  const std::string log = dir_ + "/ground.lcmlog", video = dir_ + "/ground.mp4";
  ChildProcess logger({"ip", "netns", "exec", "ground", "lcm-logger", "-f", "-q", "--lcm-url=" + kUrlTtl1, log});
  ChildProcess view({"ip", "netns", "exec", "ground", bin + "/gpilot-view", "--headless", "--video", video,
                     "--lcm-url", kUrlTtl1});
  usleep(500'000);
  ChildProcess drone({"ip", "netns", "exec", "drone", bin + "/gpilot-launch", "--services", src + "/deploy/services.yaml",
                      "--engage", "--duration", "12", "--lcm-url", kUrlTtl1,
                      "--var", "config=" + src + "/deploy/config/synthetic.yaml", "--var", "source_flag=--synthetic",
                      "--var", "source=" + src + "/deploy/scenarios/tour.yaml", "--var", "capture_extra=",
                      "--var", "backend=sim", "--var", "mavlink=udp:127.0.0.1:14580", "--var", "log=",
                      "--var", "video_out="});
  const int status = drone.wait();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "gpilot-launch on the drone failed";
  usleep(300'000);
  view.stop(SIGINT);
  logger.stop(SIGINT);

  const Heard h = read_log(log);
  for (const char* ch : {"CAMERA", "GROUND_TRUTH", "USER_TRACK", "HAND_OBS", "GESTURE_CMD", "FLIGHT_CONTROL",
                         "FLIGHT_SETPOINT", "VEHICLE_STATE", "HEALTH"})
    EXPECT_GT(h.channels.count(ch) ? h.channels.at(ch) : 0, 0) << "the ground station never heard " << ch;
  // 12 s at 25 fps, less start-up: most frames (921 kB each, in fragments) cross the link.
  EXPECT_GT(h.channels.count("CAMERA") ? h.channels.at("CAMERA") : 0, 200);
  for (const char* name : {"gpilot-capture", "gpilot-tracker", "gpilot-hands", "gpilot-decide", "gpilot-flight", "gpilot-launch"})
    EXPECT_GT(h.health.count(name) ? h.health.at(name) : 0, 5) << "no HEALTH from " << name << " on the drone";
  // The ground station's own view drew what it heard.
  EXPECT_TRUE(fs::exists(video) && fs::file_size(video) > 10'000) << "no video on the ground station";
}

TEST_F(TwoHosts, AtTtlZeroNothingLeavesTheDrone) {
  const std::string src = GPILOT_SOURCE_DIR, bin = GPILOT_BIN_DIR;
  const std::string log = dir_ + "/ground.lcmlog", local = dir_ + "/drone.lcmlog";
  ChildProcess logger({"ip", "netns", "exec", "ground", "lcm-logger", "-f", "-q", "--lcm-url=" + kUrlTtl0, log});
  ChildProcess on_drone({"ip", "netns", "exec", "drone", "lcm-logger", "-f", "-q", "--lcm-url=" + kUrlTtl0, local});
  usleep(500'000);
  sh("ip netns exec drone " + bin + "/gpilot-capture --synthetic tour --duration 1 --lcm-url '" + kUrlTtl0 + "' 2> /dev/null");
  usleep(300'000);
  logger.stop(SIGINT);
  on_drone.stop(SIGINT);
  EXPECT_GT(read_log(local).channels["CAMERA"], 10) << "the drone itself heard nothing: the check proves nothing";
  EXPECT_EQ(read_log(log).channels.size(), 0u) << "ttl=0 traffic reached the ground station";
}

}  // namespace
}  // namespace gpilot
