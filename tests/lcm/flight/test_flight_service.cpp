// gpilot-decide + gpilot-flight + gpilot-ctl as real processes on real LCM (inside a private network namespace):
// HAND_OBS in, GESTURE_CMD, FLIGHT_SETPOINT and the simulator's VEHICLE_STATE out; and gpilot-flight's MAVLink
// backend against a fake autopilot on 127.0.0.1 (HEARTBEAT, setpoint stream while engaged, COMMAND_LONG,
// LOCAL_POSITION_NED back to VEHICLE_STATE, bad bytes counted); a refused config ends it before the bus.
#include <gtest/gtest.h>

#include <cstring>

#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus_node.hpp"
#include "child_process.hpp"
#include "clock.hpp"
#include "mavlink/frame.hpp"
#include "mavlink/messages.hpp"
#include "run_command.hpp"
#include "udp_socket.hpp"
#include "user_track_fixture.hpp"

namespace gpilot {
namespace {

const std::string kBin = GPILOT_BIN_DIR;

using test::ChildProcess;

// gpilot-ctl COMMAND, run to its end; true when it exited 0.
bool ctl(const std::string& command) {
  return ChildProcess({kBin + "/gpilot-ctl", command, "--lcm-url", kDefaultLcmUrl}).wait() == 0;
}

template <class Msg>
struct Inbox {
  std::vector<Msg> got;
  void on(const lcm::ReceiveBuffer*, const std::string&, const Msg* m) { got.push_back(*m); }
};

class Bus {
 public:
  Bus() : lc_(kDefaultLcmUrl) {}
  bool good() { return lc_.good(); }
  template <class Msg>
  void listen(const std::string& channel, Inbox<Msg>& inbox) {
    lc_.subscribe(channel, &Inbox<Msg>::on, &inbox);
  }
  template <class Msg>
  void publish(const std::string& channel, const Msg& m) {
    lc_.publish(channel, &m);
  }
  // Handles messages for `seconds` (the MAVLink test's windows).
  void pump(double seconds) {
    const int64_t end = monotonic_utime() + seconds_to_utime(seconds);
    for (int64_t now; (now = monotonic_utime()) < end;)
      lc_.handleTimeout(static_cast<int>(std::max<int64_t>(1, (end - now) / 1000)));
  }
  // Handles messages until pred(), calling tick every period_s (a camera's frames); returns pred(). timeout_s
  // only ends a failing run: what is judged is what the processes said, never how long the test waited.
  bool pump_until(const std::function<bool()>& pred, double timeout_s, double period_s = 0.0,
                  const std::function<void()>& tick = {}) {
    const int64_t end = monotonic_utime() + seconds_to_utime(timeout_s);
    int64_t next = monotonic_utime();
    for (int64_t now; !pred() && (now = monotonic_utime()) < end;) {
      if (tick && now >= next) {
        tick();
        next += seconds_to_utime(period_s);
      }
      const int64_t until = tick ? std::min(next, end) : end;
      lc_.handleTimeout(static_cast<int>(std::clamp<int64_t>((until - now) / 1000, 1, 20)));
    }
    return pred();
  }
  // Pumps until pred() or timeout; returns pred().
  bool wait_for(const std::function<bool()>& pred, double timeout_s) { return pump_until(pred, timeout_s); }

 private:
  lcm::LCM lc_;
};

bool has_health(const Inbox<health_t>& h, const std::string& name) {
  for (const auto& m : h.got)
    if (m.name == name) return true;
  return false;
}

TEST(FlightService, PointingMovesTheSimulatedDroneWestOnlyWhileEngaged) {
  Bus bus;
  ASSERT_TRUE(bus.good());
  Inbox<health_t> health;
  Inbox<gesture_cmd_t> cmds;
  Inbox<flight_setpoint_t> setpoints;
  Inbox<vehicle_state_t> states;
  bus.listen("HEALTH", health);
  bus.listen("GESTURE_CMD", cmds);
  bus.listen("FLIGHT_SETPOINT", setpoints);
  bus.listen("VEHICLE_STATE", states);
  ChildProcess decide({kBin + "/gpilot-decide", "--lcm-url", kDefaultLcmUrl});
  ChildProcess flight({kBin + "/gpilot-flight", "--lcm-url", kDefaultLcmUrl});
  ASSERT_TRUE(decide.running() && flight.running());
  ASSERT_TRUE(bus.wait_for([&] { return has_health(health, "gpilot-decide") && has_health(health, "gpilot-flight"); }, 10));
  ASSERT_TRUE(bus.wait_for([&] { return !setpoints.got.empty() && !states.got.empty(); }, 5));

  // Not engaged: zero setpoints that say so.
  EXPECT_TRUE(setpoints.got.back().reasons & flight_setpoint_t::REASON_NOT_ENGAGED);
  EXPECT_FALSE(setpoints.got.back().engaged);

  // The user, centred, pointing to their right (hand on the image's left) at 25 fps.
  int64_t seq = 0, last_frame_utime = 0;
  auto frame = [&] {
    const int64_t now = last_frame_utime = wall_utime();
    const user_track_t t = test::manual_track(seq, now, {270, 100, 100, 300}, 640, 480);
    bus.publish("USER_TRACK", t);
    hand_obs_t h{};
    h.utime = now;
    h.seq = seq;
    h.track_id = 1;
    h.track_status = user_track_t::STATUS_TRACKING;
    for (int i = 0; i < 4; ++i) h.user_box[i] = t.box[i];
    h.kind = hand_obs_t::KIND_OUT;
    h.vector[0] = -50;  // half a box width to the image's left
    h.vector[1] = 0;
    h.image_width = 640;
    h.image_height = 480;
    bus.publish("HAND_OBS", h);
    ++seq;
  };
  // Pointing while NOT engaged, 50 frames: each gives its command, nothing moves.
  constexpr int64_t kFramesNotEngaged = 50;
  ASSERT_TRUE(bus.pump_until([&] { return !cmds.got.empty() && cmds.got.back().seq == kFramesNotEngaged - 1; }, 20, 0.04,
                             [&] {
                               if (seq < kFramesNotEngaged) frame();
                             }));
  const vehicle_state_t before = states.got.back();
  EXPECT_EQ(cmds.got.back().mode, gesture_cmd_t::MODE_FINE);
  EXPECT_NEAR(cmds.got.back().direction[0], -0.5, 1e-6);
  EXPECT_EQ(cmds.got.size(), static_cast<size_t>(kFramesNotEngaged));  // one GESTURE_CMD per HAND_OBS, with its seq
  EXPECT_TRUE(setpoints.got.back().reasons & flight_setpoint_t::REASON_NOT_ENGAGED);
  EXPECT_EQ(setpoints.got.back().velocity[1], 0.0f);

  // Engaged: judged after 2 s of the simulator's own time (its steps, one VEHICLE_STATE each at sim.rate_hz
  // 100) from the first setpoint that moves it, however long the machine takes to run them.
  ASSERT_TRUE(ctl("engage"));
  constexpr size_t kSimSteps = 200;
  std::optional<size_t> moving_from;  // states.got's size when the first moving setpoint came
  const auto flown = [&] {
    if (!moving_from && !setpoints.got.empty() && setpoints.got.back().engaged && setpoints.got.back().velocity[1] < 0)
      moving_from = states.got.size();
    return moving_from && states.got.size() >= *moving_from + kSimSteps;
  };
  ASSERT_TRUE(bus.pump_until(flown, 30, 0.04, frame));
  const vehicle_state_t after = states.got.back();
  const flight_setpoint_t sp = setpoints.got.back();
  EXPECT_TRUE(sp.engaged);
  EXPECT_EQ(sp.reasons & ~flight_setpoint_t::REASON_COMMAND_DELAY, 0);
  EXPECT_FLOAT_EQ(sp.velocity[1], -0.5f);  // body left = the user's right
  EXPECT_LT(after.position[1] - before.position[1], -0.3);  // facing north: west (2 s at up to 0.5 m/s)
  EXPECT_NEAR(after.position[0], before.position[0], 0.1);
  EXPECT_EQ(after.source, vehicle_state_t::SOURCE_SIMULATOR);

  // The user vanishes (no more frames): the setpoints become zero and say why, once flight.stale_timeout_s
  // (0.25 s) has passed on gpilot-flight's clock since the last frame was sent.
  const size_t since = setpoints.got.size();
  const auto first_stale = [&]() -> const flight_setpoint_t* {
    for (size_t i = since; i < setpoints.got.size(); ++i)
      if (setpoints.got[i].reasons & flight_setpoint_t::REASON_STALE_COMMAND) return &setpoints.got[i];
    return nullptr;
  };
  ASSERT_TRUE(bus.wait_for([&] { return first_stale() != nullptr; }, 10));
  const flight_setpoint_t stale = *first_stale();
  EXPECT_EQ(stale.velocity[1], 0.0f);
  EXPECT_TRUE(stale.reasons & flight_setpoint_t::REASON_STALE_TRACK);
  EXPECT_GT(stale.utime - last_frame_utime, seconds_to_utime(0.25));

  ASSERT_TRUE(ctl("land"));
  ASSERT_TRUE(bus.wait_for([&] {
    return (setpoints.got.back().reasons & flight_setpoint_t::REASON_LANDING) &&
           states.got.back().landed_state == vehicle_state_t::LANDED_LANDING;
  }, 10));
  EXPECT_EQ(flight.stop() & 0x7f, 0);  // exited on SIGTERM by itself, no crash
}

// gpilot-flight with `args`, for at most 10 s: its exit status (124: still running then) and its stderr.
test::CommandOutput run_flight(const std::string& args) {
  return test::run_command("timeout 10 " + kBin + "/gpilot-flight --lcm-url '" + std::string(kDefaultLcmUrl) + "' " +
                           args + " 2>&1 >/dev/null");
}

// GIVEN a backend or an autopilot that is not one of the choices (or an endpoint that does not parse) WHEN
// gpilot-flight starts THEN it exits 2 naming the key, before it says anything on the bus (the sections' check()
// refuses them while the config is read; the service itself no longer checks them).
TEST(FlightService, RefusesAnUnknownBackendOrAutopilotBeforeTheBus) {
  Bus bus;
  ASSERT_TRUE(bus.good());
  Inbox<health_t> health;
  bus.listen("HEALTH", health);
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"--set flight.backend=simm", "flight.backend: 'simm' is not one of sim, mavlink, none"},
      {"--set flight.backend=mavlink --set mavlink.autopilot=px5", "mavlink.autopilot: 'px5' is not one of px4, ardupilot"},
      {"--set flight.backend=sim --set mavlink.autopilot=px5", "mavlink.autopilot: 'px5' is not one of px4, ardupilot"},
      {"--set flight.backend=mavlink --set mavlink.endpoint=udp:nohost", "mavlink.endpoint: "},
  };
  for (const auto& [args, says] : refused) {
    const test::CommandOutput e = run_flight(args);
    EXPECT_EQ(e.code, 2) << args << "\n" << e.out;
    EXPECT_NE(e.out.find("gpilot-flight: error: config error: " + says), std::string::npos) << args << "\n" << e.out;
  }
  bus.pump(0.3);
  EXPECT_FALSE(has_health(health, "gpilot-flight")) << "a refused gpilot-flight came on the bus";
}

// The fake autopilot: a UDP socket on 127.0.0.1 that answers whoever wrote to it.
class FakeAutopilot {
 public:
  int port() const { return socket_.port(); }
  // Reads what has arrived (for up to 10 ms) into frames.
  void poll() {
    std::vector<uint8_t> buf;
    if (!socket_.receive(buf, &peer_)) return;
    have_peer_ = true;
    parser_.feed(buf.data(), buf.size(), [&](const mavlink::Frame& f) { frames.push_back(f); });
    parser_.end_of_datagram();
  }
  void send(const std::vector<uint8_t>& bytes) {
    if (have_peer_) socket_.send_to(peer_, bytes.data(), bytes.size());
  }
  int count(uint32_t msgid) const {
    int n = 0;
    for (const auto& f : frames) n += f.msgid == msgid ? 1 : 0;
    return n;
  }
  std::vector<mavlink::Frame> frames;
  bool have_peer_ = false;

 private:
  test::UdpSocket socket_;
  sockaddr_in peer_{};
  mavlink::FrameParser parser_;
};

template <class M>
std::vector<uint8_t> from_autopilot(const M& m, uint8_t seq) {
  return mavlink::encode_frame({seq, 1, 1, M::kId, mavlink::pack(m)});
}

TEST(FlightService, MavlinkBackendTalksToAnAutopilotOnLoopback) {
  Bus bus;
  ASSERT_TRUE(bus.good());
  FakeAutopilot ap;
  Inbox<vehicle_state_t> states;
  Inbox<health_t> health;
  bus.listen("VEHICLE_STATE", states);
  bus.listen("HEALTH", health);
  ChildProcess flight({kBin + "/gpilot-flight", "--lcm-url", kDefaultLcmUrl, "--set", "flight.backend=mavlink", "--set",
                       "mavlink.endpoint=udp:127.0.0.1:" + std::to_string(ap.port())});
  auto run = [&](double seconds, const std::function<void()>& each = {}) {
    const int64_t end = monotonic_utime() + seconds_to_utime(seconds);
    while (monotonic_utime() < end) {
      ap.poll();
      if (each) each();
      bus.pump(0.005);
    }
  };
  // Runs until pred() (timeout_s only ends a failing run); returns pred().
  auto run_until = [&](const std::function<bool()>& pred, double timeout_s, const std::function<void()>& each = {}) {
    const int64_t end = monotonic_utime() + seconds_to_utime(timeout_s);
    while (!pred() && monotonic_utime() < end) run(0.005, each);
    return pred();
  };
  // Our HEARTBEAT arrives (sent at start and at 1 Hz).
  ASSERT_TRUE(run_until([&] { return ap.count(mavlink::Heartbeat::kId) >= 1; }, 10.0));
  ASSERT_TRUE(ap.have_peer_);
  EXPECT_EQ(ap.count(mavlink::SetPositionTargetLocalNed::kId), 0);  // not engaged: no setpoints

  // The autopilot answers: armed PX4, a position and an attitude -> VEHICLE_STATE from MAVLink.
  mavlink::Heartbeat hb;
  hb.autopilot = 12;
  hb.type = 2;
  hb.base_mode = 128 | 1;
  mavlink::Attitude att;
  att.yaw = 0.75f;
  mavlink::LocalPositionNed pos;
  pos.x = 1.5f;
  pos.y = -2.0f;
  pos.z = -3.0f;
  uint8_t seq = 0;
  auto answer = [&] {
    std::vector<uint8_t> d;
    for (auto b : {from_autopilot(hb, seq++), from_autopilot(att, seq++), from_autopilot(pos, seq++)})
      d.insert(d.end(), b.begin(), b.end());
    ap.send(d);
  };
  answer();
  ASSERT_TRUE(bus.wait_for([&] { return !states.got.empty(); }, 2.0));
  const vehicle_state_t s = states.got.back();
  EXPECT_EQ(s.source, vehicle_state_t::SOURCE_MAVLINK);
  EXPECT_EQ(s.position[0], 1.5f);
  EXPECT_EQ(s.position[1], -2.0f);
  EXPECT_EQ(s.position[2], -3.0f);
  EXPECT_EQ(s.attitude[2], 0.75f);
  EXPECT_TRUE(s.armed);

  // arm -> COMMAND_LONG(400, 1) once (gpilot-ctl repeats, the bridge acts once)
  ASSERT_TRUE(ctl("arm"));
  run(0.5);
  int arms = 0;
  for (const auto& f : ap.frames)
    if (f.msgid == mavlink::CommandLong::kId && mavlink::unpack_command_long(f.payload).command == 400) ++arms;
  EXPECT_EQ(arms, 1);

  // ENGAGE reads the autopilot's COM_OF_LOSS_T first: answered 3 s (the vehicle would fly on that long after
  // gpilot-flight stops), it is refused: no setpoints
  float loss_t = 3.0f;
  int answered = 0;
  auto answer_all = [&] {
    answer();
    int asked = 0;
    for (const auto& f : ap.frames) asked += f.msgid == mavlink::ParamRequestRead::kId ? 1 : 0;
    for (; answered < asked; ++answered) {
      mavlink::ParamValue v;
      std::strncpy(v.param_id, "COM_OF_LOSS_T", sizeof v.param_id);
      v.param_value = loss_t;
      v.param_type = mavlink::kMavParamTypeReal32;
      ap.send(from_autopilot(v, seq++));
    }
  };
  ASSERT_TRUE(ctl("engage"));
  run(0.5, answer_all);
  EXPECT_GE(answered, 1);
  EXPECT_EQ(ap.count(mavlink::SetPositionTargetLocalNed::kId), 0);

  // answered 0.5 s: engaged, SET_POSITION_TARGET_LOCAL_NED streams at >= 20 Hz (zero: no gesture yet), and
  // OFFBOARD is asked for
  loss_t = 0.5f;
  ASSERT_TRUE(ctl("engage"));
  constexpr int kSetpoints = 26;
  ASSERT_TRUE(run_until([&] { return ap.count(mavlink::SetPositionTargetLocalNed::kId) >= kSetpoints; }, 10.0, answer_all));
  std::vector<mavlink::SetPositionTargetLocalNed> sent;
  for (const auto& f : ap.frames)
    if (f.msgid == mavlink::SetPositionTargetLocalNed::kId) sent.push_back(mavlink::unpack_set_position_target_local_ned(f.payload));
  ASSERT_GE(sent.size(), static_cast<size_t>(kSetpoints));
  // The rate by gpilot-flight's own clock (each setpoint's time_boot_ms), not by when this test read them:
  // 25 periods at flight.setpoint_rate_hz 50 take 500 ms; at 20 Hz (PX4 leaves offboard below 2) 1250 ms.
  for (size_t i = 1; i < sent.size(); ++i) EXPECT_GE(sent[i].time_boot_ms, sent[i - 1].time_boot_ms) << i;
  const uint32_t span_ms = sent[kSetpoints - 1].time_boot_ms - sent[0].time_boot_ms;
  EXPECT_GT(span_ms, 0u);
  EXPECT_LE(span_ms, 1250u);
  bool offboard = false;
  for (const auto& f : ap.frames)
    if (f.msgid == mavlink::CommandLong::kId && mavlink::unpack_command_long(f.payload).command == 176) offboard = true;
  EXPECT_TRUE(offboard);
  // velocity-only setpoints in LOCAL_NED, zero without a gesture
  const auto& m = sent.back();
  EXPECT_EQ(m.coordinate_frame, 8);
  EXPECT_EQ(m.type_mask, 1479);
  EXPECT_EQ(m.vx, 0.0f);

  // disengage: the stream stops
  ASSERT_TRUE(ctl("disengage"));
  run(0.3);
  const int at_disengage = ap.count(mavlink::SetPositionTargetLocalNed::kId);
  run(0.5);
  EXPECT_EQ(ap.count(mavlink::SetPositionTargetLocalNed::kId), at_disengage);

  // bad bytes from the autopilot are counted in HEALTH, never a crash
  auto bad = from_autopilot(pos, seq++);
  bad[12] ^= 0xFF;
  ap.send(bad);
  health.got.clear();
  int64_t rejected = 0;
  std::string reason;
  const auto reported = [&] {
    for (const auto& h : health.got)
      if (h.name == "gpilot-flight") {
        rejected = h.rejected;
        reason = h.last_reject_reason;
      }
    return rejected >= 1;
  };
  EXPECT_TRUE(run_until(reported, 10.0));
  EXPECT_NE(reason.find("MAVLink"), std::string::npos) << reason;
  EXPECT_EQ(flight.stop() & 0x7f, 0);
}

}  // namespace
}  // namespace gpilot
