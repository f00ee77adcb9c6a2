// The flight bridge over a log (see flight_replay.hpp).
#include "flight_replay.hpp"

#include "flight/flight_messages.hpp"
#include "flight/flight_params.hpp"

namespace gpilot {

FlightReplay::FlightReplay(const Config& config, BusNode& node, const int64_t& now_ts)
    : node_(node), now_ts_(now_ts), bridge_(config.section<FlightParams>("flight")) {
  node_.subscribe<gesture_cmd_t>("GESTURE_CMD", [this](const gesture_cmd_t& m, int64_t) {
    commands_.emplace_back(now_ts_, to_core(m));
  });
  node_.subscribe<user_track_t>("USER_TRACK", [this](const user_track_t& m, int64_t) {
    tracks_.emplace_back(now_ts_, to_core(m));
  });
  node_.subscribe<vehicle_state_t>("VEHICLE_STATE", [this](const vehicle_state_t& m, int64_t) {
    in_.vehicle = to_core(m);
    in_.vehicle_received = now_ts_;
  });
  node_.subscribe<flight_control_t>("FLIGHT_CONTROL", [this](const flight_control_t& m, int64_t) {
    std::string why;
    operator_.apply(to_core(m), in_, &why);
  });
}

void FlightReplay::on_recorded_setpoint(const void* data, size_t size) {
  flight_setpoint_t recorded{};
  if (recorded.decode(data, 0, static_cast<int>(size)) < 0) return;
  in_.now = recorded.utime;  // the live bridge's own "now" for that setpoint
  while (!commands_.empty() && commands_.front().second.seq <= recorded.latest_command_seq) {
    in_.command = commands_.front().second;
    in_.command_received = commands_.front().first;
    commands_.pop_front();
  }
  while (!tracks_.empty() && recorded.track_utime != 0 && tracks_.front().second.utime <= recorded.track_utime) {
    in_.track = tracks_.front().second;
    in_.track_received = tracks_.front().first;
    tracks_.pop_front();
  }
  // The bridge's own arrival times (the logger's differ by a millisecond, which decides staleness at the edge).
  if (in_.command && in_.command->seq == recorded.latest_command_seq) in_.command_received = recorded.command_received;
  if (in_.track && in_.track->utime == recorded.track_utime) in_.track_received = recorded.track_received;
  node_.publish("FLIGHT_SETPOINT", to_message(bridge_.update(in_)));
}

}  // namespace gpilot
