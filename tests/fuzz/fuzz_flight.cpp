// Fuzz target: the flight bridge fed a sequence of GESTURE_CMD, USER_TRACK, VEHICLE_STATE and FLIGHT_CONTROL
// messages (as check_message lets them through, converted as gpilot-flight converts them) and setpoint ticks
// at times that step, stall, jump or go back. Each input is one sequence on a fresh bridge. Every setpoint
// must be finite, zero unless engaged and not landing, and within the configured speed and yaw limits.
#include <cmath>
#include <cstdint>
#include <string>

#include "flight/flight_bridge.hpp"
#include "flight/flight_messages.hpp"
#include "flight/flight_params.hpp"
#include "flight/operator_state.hpp"
#include "fuzz_input.hpp"
#include "message_checks.hpp"

namespace {

void check(const gpilot::FlightParams& p, const gpilot::BridgeInputs& in, const gpilot::Setpoint& sp) {
  const double v[4] = {sp.velocity[0], sp.velocity[1], sp.velocity[2], sp.yaw_rate};
  for (double x : v)
    if (!std::isfinite(x)) gpilot::fuzz::fail("a setpoint is not finite");
  if ((!in.engaged || in.landing) && !sp.is_zero()) gpilot::fuzz::fail("a setpoint moves while not engaged or landing");
  constexpr double kEps = 1e-9;
  if (std::hypot(v[0], v[1]) > p.max_horizontal_speed + kEps) gpilot::fuzz::fail("horizontal speed above its limit");
  if (std::fabs(v[2]) > p.max_vertical_speed + kEps) gpilot::fuzz::fail("vertical speed above its limit");
  if (std::fabs(v[3]) > p.max_yaw_rate + kEps) gpilot::fuzz::fail("yaw rate above its limit");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  gpilot::fuzz::Input in(data, size);
  const gpilot::FlightParams params;
  gpilot::FlightBridge bridge(params);
  gpilot::OperatorState op;
  gpilot::BridgeInputs inputs;
  inputs.now = 1'700'000'000'000'000 + in.in(0, 1'000'000);
  for (int64_t step = 0; step < 300 && !in.empty(); ++step) {
    const uint8_t what = in.byte();
    const uint8_t when = in.byte();
    inputs.now += when < 200 ? 20'000 : when < 250 ? in.in(-2'000'000, 2'000'000) : in.raw<int32_t>();
    switch (what % 5) {
      case 0: {
        gpilot::gesture_cmd_t m{};
        m.utime = inputs.now - in.in(0, 200'000);
        m.seq = step;
        m.track_id = static_cast<int32_t>(in.in(0, 2));
        m.mode = static_cast<int8_t>(in.byte() % 6);
        for (float& d : m.direction) d = in.byte() < 200 ? in.coordinate() / 512.0f - 2.0f : in.f32();
        m.user_box_width = in.byte() < 200 ? 120.0f : in.f32();
        if (!gpilot::check_message(m).empty()) break;
        inputs.command = gpilot::to_core(m);
        inputs.command_received = inputs.now;
        break;
      }
      case 1: {
        gpilot::user_track_t m{};
        m.utime = inputs.now - in.in(0, 200'000);
        m.seq = step;
        m.status = static_cast<int8_t>(in.byte() % 3);
        m.track_id = static_cast<int32_t>(in.in(0, 2));
        m.image_width = in.byte() < 240 ? 640 : static_cast<int32_t>(in.in(0, 2000));
        m.image_height = in.byte() < 240 ? 480 : static_cast<int32_t>(in.in(0, 2000));
        for (float& b : m.box) b = in.byte() < 240 ? in.coordinate() / 2.0f : in.f32();
        if (!gpilot::check_message(m).empty()) break;
        inputs.track = gpilot::to_core(m);
        inputs.track_received = inputs.now;
        break;
      }
      case 2: {
        gpilot::vehicle_state_t m{};
        m.utime = inputs.now;
        m.seq = step;
        m.source = gpilot::vehicle_state_t::SOURCE_SIMULATOR;
        m.landed_state = static_cast<int8_t>(in.byte() % 5);
        m.armed = in.flag();
        for (float& x : m.position) x = in.byte() < 240 ? in.coordinate() / 64.0f - 16.0f : in.f32();
        for (float& x : m.velocity) x = in.coordinate() / 256.0f - 4.0f;
        for (float& x : m.attitude) x = in.coordinate() / 1024.0f - 1.0f;
        m.yaw_rate = in.coordinate() / 1024.0f - 1.0f;
        if (!gpilot::check_message(m).empty()) break;
        inputs.vehicle = gpilot::to_core(m);
        inputs.vehicle_received = inputs.now;
        break;
      }
      case 3: {
        gpilot::flight_control_t m{};
        m.utime = inputs.now;
        m.seq = in.in(0, 3);  // repeats are part of the protocol (gpilot-ctl sends each request a few times)
        m.command = static_cast<int8_t>(1 + in.byte() % 6);
        m.takeoff_altitude = in.byte() < 200 ? in.coordinate() / 100.0f : in.f32();
        m.source = in.flag() ? "gpilot-ctl" : "fuzz";
        if (!gpilot::check_message(m).empty()) break;
        std::string why;
        (void)op.apply(gpilot::to_core(m), inputs, &why);
        break;
      }
      default: {
        const gpilot::Setpoint sp = bridge.update(inputs);
        check(params, inputs, sp);
        break;
      }
    }
  }
  return 0;
}
