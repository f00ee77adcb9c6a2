// The flight service on the node's clock (start_flight_service on memq://, the log's clock as in a replay):
// a setpoint only when the timer fires, stamped with the node's time then, naming the command and track it had;
// an input's age counted from the first tick that had it (what a replay reproduces from the log).
#include <gtest/gtest.h>

#include <vector>

#include "bus_node.hpp"
#include "config.hpp"
#include "flight/flight_service.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"

namespace gpilot {
namespace {

constexpr int64_t kT0 = 1'800'000'000'000'000;
constexpr int64_t kMs = 1000;

class FlightServiceClock : public ::testing::Test {
 protected:
  void SetUp() override {
    Config config;
    config.set("flight.backend=none");  // vehicle states from the bus, as in a replay
    node.set_log_time(kT0);
    node.subscribe<flight_setpoint_t>("FLIGHT_SETPOINT", [this](const flight_setpoint_t& m, int64_t) { got.push_back(m); });
    service = start_flight_service(config, node);
  }

  // ENGAGE, a HOVER command of frame 7, the user tracked in the middle of the image, a vehicle state: all at kT0.
  void inputs_at_t0() {
    flight_control_t engage{};
    engage.utime = kT0;
    engage.source = "test";
    engage.command = flight_control_t::COMMAND_ENGAGE;
    node.publish("FLIGHT_CONTROL", engage);
    gesture_cmd_t cmd{};
    cmd.utime = kT0;
    cmd.seq = 7;
    cmd.track_id = 1;
    cmd.mode = gesture_cmd_t::MODE_HOVER;
    cmd.user_box_width = 100;
    node.publish("GESTURE_CMD", cmd);
    user_track_t track{};
    track.utime = kT0;
    track.seq = 7;
    track.status = user_track_t::STATUS_TRACKING;
    track.box[0] = 270; track.box[1] = 100; track.box[2] = 100; track.box[3] = 200;
    track.confidence = 10;
    track.init_source = user_track_t::INIT_FACE;
    track.track_id = 1;
    track.image_width = 640;
    track.image_height = 480;
    node.publish("USER_TRACK", track);
    vehicle_state_t v{};
    v.utime = kT0;
    v.seq = 1;
    v.position[2] = -2.0f;
    v.armed = true;
    v.source = vehicle_state_t::SOURCE_SIMULATOR;
    v.landed_state = vehicle_state_t::LANDED_IN_AIR;
    node.publish("VEHICLE_STATE", v);
    node.drain();
  }

  BusNode node{"gpilot-test", "memq://"};
  std::shared_ptr<void> service;
  std::vector<flight_setpoint_t> got;
};

TEST_F(FlightServiceClock, ASetpointOnlyWhenTheTimerFiresStampedWithTheNodesTime) {
  // GIVEN the service on the log's clock WHEN inputs arrive and the bus is drained
  inputs_at_t0();
  // THEN no setpoint: in replay its timer does not fire by itself
  EXPECT_TRUE(got.empty());
  // WHEN the timer fires at kT0 + 10 ms
  node.run_timers_at(kT0 + 10 * kMs);
  node.drain();
  // THEN one setpoint of that instant, from the inputs it had, engaged and passed unchanged
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].utime, kT0 + 10 * kMs);
  EXPECT_EQ(got[0].latest_command_seq, 7);
  EXPECT_EQ(got[0].track_utime, kT0);
  EXPECT_EQ(got[0].control_utime, kT0);  // the ENGAGE it had
  EXPECT_TRUE(got[0].engaged);
  EXPECT_EQ(got[0].reasons, 0) << got[0].reasons;
}

TEST_F(FlightServiceClock, AnInputsAgeCountsFromTheFirstTickThatHadIt) {
  // GIVEN inputs that arrived at kT0 and a first tick at kT0 + 10 ms that had them
  inputs_at_t0();
  node.run_timers_at(kT0 + 10 * kMs);
  // WHEN ticks follow with nothing new: at 250 ms and 251 ms after that first tick (260 / 261 ms after arrival)
  node.run_timers_at(kT0 + 260 * kMs);
  node.run_timers_at(kT0 + 261 * kMs);
  node.drain();
  // THEN the first is still fresh (flight.stale_timeout_s 0.25 from the tick), the second is stale on all three
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[1].reasons, 0) << got[1].reasons;
  EXPECT_EQ(got[2].reasons, flight_setpoint_t::REASON_STALE_COMMAND | flight_setpoint_t::REASON_STALE_TRACK |
                                flight_setpoint_t::REASON_STALE_VEHICLE)
      << got[2].reasons;
}

}  // namespace
}  // namespace gpilot
