// Two hosts, as a drone and its ground station are deployed: two network namespaces joined by a veth pair
// with a multicast route, LCM at ttl=1. Perception and flight run on "drone" (gpilot-launch with
// deploy/services.yaml, no logger and no video there), gpilot-view and gpilot-record on "ground". The ground
// station receives every channel; at ttl=0 (the default) nothing leaves the drone; and with the deployment's
// bus key only its holders fly it: an attacker on the network without the key (forged ENGAGE, TRACKER_INIT,
// GESTURE_CMD and USER_TRACK floods, LAND, a replayed ENGAGE) is rejected and counted, the vehicle holds.
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

#include "bus_key.hpp"
#include "child_process.hpp"
#include "clock.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/vehicle_state_t.hpp"

namespace fs = std::filesystem;

namespace gpilot {
namespace {

const std::string kUrlTtl1 = "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4194304";
const std::string kUrlTtl0 = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
// The frames' URL (bus.frames_url's default: port + 1)
const std::string kFramesUrlTtl0 = "udpm://239.255.76.67:7668?ttl=0&recv_buf_size=4194304";

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
    // One deployment key, on both hosts (the processes read GPILOT_BUS_KEY): a ttl=1 bus needs one.
    make_bus_key_file(dir_ + "/bus.key");
    ::setenv("GPILOT_BUS_KEY", (dir_ + "/bus.key").c_str(), 1);
    sh("ip netns add drone && ip netns add ground && ip link add veth-d type veth peer name veth-g && "
       "ip link set veth-d netns drone && ip link set veth-g netns ground && "
       "ip -n drone addr add 10.77.0.1/24 dev veth-d && ip -n ground addr add 10.77.0.2/24 dev veth-g && "
       "ip -n drone link set lo up && ip -n ground link set lo up && "
       "ip -n drone link set veth-d up && ip -n ground link set veth-g up && "
       "ip -n drone route add 224.0.0.0/4 dev veth-d && ip -n ground route add 224.0.0.0/4 dev veth-g");
  }
  void TearDown() override {
    ::unsetenv("GPILOT_BUS_KEY");
    std::system("ip netns del drone 2>/dev/null; ip netns del ground 2>/dev/null");
    if (!HasFailure() && !dir_.empty()) fs::remove_all(dir_);
  }
  std::string dir_;
};

TEST_F(TwoHosts, GroundStationHearsEveryChannelOfTheDrone) {
  const std::string src = GPILOT_SOURCE_DIR, bin = GPILOT_BIN_DIR;
  const std::string log = dir_ + "/ground.lcmlog", video = dir_ + "/ground.mp4";
  // gpilot-record: the bus and the frames' URL (CAMERA travels on a port of its own) into one log
  ChildProcess logger({"ip", "netns", "exec", "ground", bin + "/gpilot-record", "--lcm-url", kUrlTtl1, log});
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
  const std::string frames_log = dir_ + "/ground-frames.lcmlog";
  ChildProcess logger({"ip", "netns", "exec", "ground", "lcm-logger", "-f", "-q", "--lcm-url=" + kUrlTtl0, log});
  ChildProcess frames_logger(
      {"ip", "netns", "exec", "ground", "lcm-logger", "-f", "-q", "--lcm-url=" + kFramesUrlTtl0, frames_log});
  ChildProcess on_drone({"ip", "netns", "exec", "drone", bin + "/gpilot-record", "--lcm-url", kUrlTtl0, local});
  usleep(500'000);
  sh("ip netns exec drone " + bin + "/gpilot-capture --synthetic tour --duration 1 --lcm-url '" + kUrlTtl0 + "' 2> /dev/null");
  usleep(300'000);
  logger.stop(SIGINT);
  frames_logger.stop(SIGINT);
  on_drone.stop(SIGINT);
  EXPECT_GT(read_log(local).channels["CAMERA"], 10) << "the drone itself heard nothing: the check proves nothing";
  EXPECT_EQ(read_log(log).channels.size(), 0u) << "ttl=0 traffic reached the ground station";
  EXPECT_EQ(read_log(frames_log).channels.size(), 0u) << "ttl=0 frames reached the ground station";
}

struct Flown {
  std::vector<std::pair<int64_t, flight_setpoint_t>> setpoints;  // (logger time, message)
  std::vector<std::pair<int64_t, vehicle_state_t>> states;
  std::map<std::string, health_t> last_health;
};

Flown read_flight(const std::string& path) {
  Flown f;
  lcm::LogFile log(path, "r");
  for (const lcm::LogEvent* ev = log.good() ? log.readNextEvent() : nullptr; ev; ev = log.readNextEvent()) {
    const std::string ch = ev->channel;
    if (ch == "FLIGHT_SETPOINT") {
      flight_setpoint_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) f.setpoints.emplace_back(ev->timestamp, m);
    } else if (ch == "VEHICLE_STATE") {
      vehicle_state_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) f.states.emplace_back(ev->timestamp, m);
    } else if (ch == "HEALTH") {
      health_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) f.last_health[m.name] = m;
    }
  }
  return f;
}

TEST_F(TwoHosts, OnlyTheKeyHolderFliesIt) {
  const std::string src = GPILOT_SOURCE_DIR, bin = GPILOT_BIN_DIR, attacker = GPILOT_ATTACKER;
  const std::string log = dir_ + "/ground.lcmlog";
  ChildProcess logger({"ip", "netns", "exec", "ground", "lcm-logger", "-f", "-q", "--lcm-url=" + kUrlTtl1,
                       "--channel=FLIGHT_SETPOINT|VEHICLE_STATE|HEALTH|FLIGHT_CONTROL", log});
  usleep(500'000);
  // GIVEN the drone flying the idle scenario, never engaged by its operator
  ChildProcess drone({"ip", "netns", "exec", "drone", bin + "/gpilot-launch", "--services", src + "/deploy/services.yaml",
                      "--duration", "16", "--lcm-url", kUrlTtl1,
                      "--var", "config=" + src + "/deploy/config/synthetic.yaml", "--var", "source_flag=--synthetic",
                      "--var", "source=" + src + "/deploy/scenarios/idle.yaml", "--var", "capture_extra=",
                      "--var", "backend=sim", "--var", "mavlink=udp:127.0.0.1:14580", "--var", "log=",
                      "--var", "video_out="});
  sleep(4);
  // WHEN a host without the key forges ENGAGE, TRACKER_INIT, 1 s of GESTURE_CMD and USER_TRACK, and LAND
  const int64_t attack_from = wall_utime();
  ChildProcess replayer({"ip", "netns", "exec", "ground", "env", "-u", "GPILOT_BUS_KEY", attacker, kUrlTtl1, "replay", "10"});
  sh("ip netns exec ground env -u GPILOT_BUS_KEY " + attacker + " '" + kUrlTtl1 + "' forge");
  usleep(500'000);
  // AND the ground station, with the key, engages and disengages; the attacker then replays the ENGAGE it heard
  sh("ip netns exec ground " + bin + "/gpilot-ctl engage --lcm-url '" + kUrlTtl1 + "'");
  const int64_t engaged_at = wall_utime();
  sleep(2);
  const int64_t disengage_from = wall_utime();
  sh("ip netns exec ground " + bin + "/gpilot-ctl disengage --lcm-url '" + kUrlTtl1 + "'");
  const int64_t disengaged_at = wall_utime();
  const int replayed = replayer.wait();
  EXPECT_TRUE(WIFEXITED(replayed) && WEXITSTATUS(replayed) == 0) << "the attacker did not replay an ENGAGE";
  const int status = drone.wait();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "gpilot-launch on the drone failed";
  usleep(300'000);
  logger.stop(SIGINT);

  const Flown f = read_flight(log);
  ASSERT_GT(f.setpoints.size(), 100u) << "the ground station heard no flight";
  int attacked = 0, engaged_by_operator = 0, after_replay = 0;
  for (const auto& [t, s] : f.setpoints) {
    if (t >= attack_from && t < engaged_at - 200'000) {
      // THEN nothing the attacker sent engaged the vehicle or moved it
      ++attacked;
      EXPECT_FALSE(s.engaged) << "engaged by the attacker at +" << (t - attack_from) / 1000 << " ms";
      EXPECT_EQ(std::abs(s.velocity[0]) + std::abs(s.velocity[1]) + std::abs(s.velocity[2]), 0.0f);
    } else if (t > engaged_at + 300'000 && t < disengage_from) {
      engaged_by_operator += s.engaged;
    } else if (t > disengaged_at + 300'000) {
      ++after_replay;
      EXPECT_FALSE(s.engaged) << "the replayed ENGAGE engaged it at +" << (t - disengaged_at) / 1000 << " ms";
    }
  }
  EXPECT_GT(attacked, 20);
  EXPECT_GT(after_replay, 20);
  // AND the operator with the key still flies it over ttl=1
  EXPECT_GT(engaged_by_operator, 20) << "gpilot-ctl engage with the key did not engage";
  // AND the vehicle held its height through LAND and the rest
  float z0 = 0, zmin = 1e9f, zmax = -1e9f;
  for (const auto& [t, v] : f.states)
    if (t >= attack_from && t < engaged_at) {
      if (zmin > zmax) z0 = v.position[2];
      zmin = std::min(zmin, v.position[2]);
      zmax = std::max(zmax, v.position[2]);
    }
  ASSERT_LE(zmin, zmax) << "no VEHICLE_STATE during the attack";
  EXPECT_LT(zmax - zmin, 0.05f) << "height moved during the attack (from " << z0 << ")";
  // AND the stages counted what they refused, with the reason
  ASSERT_TRUE(f.last_health.count("gpilot-flight"));
  const health_t& flight = f.last_health.at("gpilot-flight");
  EXPECT_GE(flight.rejected, 200 + 2 + 200 + 3) << flight.last_reject_reason;  // GESTURE_CMD, controls, USER_TRACK, replays
  ASSERT_TRUE(f.last_health.count("gpilot-tracker"));
  EXPECT_GE(f.last_health.at("gpilot-tracker").rejected, 1) << "the forged TRACKER_INIT was not refused";
}

}  // namespace
}  // namespace gpilot
