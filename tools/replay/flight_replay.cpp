// The flight bridge over a log (see flight_replay.hpp).
#include "flight_replay.hpp"

#include "flight/flight_messages.hpp"
#include "flight/flight_params.hpp"

namespace gpilot {

FlightReplay::FlightReplay(const Config& config, BusNode& node, const int64_t& now_ts)
    : node_(node), now_ts_(now_ts), bridge_(config.section<FlightParams>("flight")) {
  node_.subscribe<gesture_cmd_t>("GESTURE_CMD", [this](const gesture_cmd_t& m, int64_t) {
    later([this, c = to_core(m), t = now_ts_] {
      in_.command = c;
      in_.command_received = t;
    });
  });
  node_.subscribe<user_track_t>("USER_TRACK", [this](const user_track_t& m, int64_t) {
    later([this, u = to_core(m), t = now_ts_] {
      in_.track = u;
      in_.track_received = t;
    });
  });
  node_.subscribe<vehicle_state_t>("VEHICLE_STATE", [this](const vehicle_state_t& m, int64_t) {
    later([this, v = to_core(m), t = now_ts_] {
      in_.vehicle = v;
      in_.vehicle_received = t;
    });
  });
  node_.subscribe<flight_control_t>("FLIGHT_CONTROL", [this](const flight_control_t& m, int64_t) {
    later([this, r = to_core(m)] {
      std::string why;
      operator_.apply(r, in_, &why);
    });
  });
}

void FlightReplay::on_recorded_setpoint(const void* data, size_t size) {
  flight_setpoint_t recorded{};
  if (recorded.decode(data, 0, static_cast<int>(size)) < 0) return;
  in_.now = recorded.utime;  // the live bridge's own "now" for that setpoint
  while (!pending_.empty() && pending_.front().first <= in_.now) {
    pending_.front().second();
    pending_.pop_front();
  }
  node_.publish("FLIGHT_SETPOINT", to_message(bridge_.update(in_)));
}

}  // namespace gpilot
