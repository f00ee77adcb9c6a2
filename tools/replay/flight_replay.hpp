// The flight stage in a replay: the bridge (the same FlightBridge and OperatorState as gpilot-flight) fed the
// logged GESTURE_CMD, USER_TRACK, VEHICLE_STATE and FLIGHT_CONTROL with their log times as receipt times, and
// asked for a setpoint at each recorded FLIGHT_SETPOINT's own time, from the inputs that had arrived by then
// (the logger may write an input before a setpoint the bridge computed just before that input reached it).
// The vehicle is not simulated again: its states come from the log, so this replays the decisions (zeroing,
// spacing, limits, yaw), not the flight.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>

#include "bus_node.hpp"
#include "config.hpp"
#include "flight/flight_bridge.hpp"
#include "flight/operator_state.hpp"

namespace gpilot {

class FlightReplay {
 public:
  // now_ts: the log time of the event being replayed (read when an input arrives).
  FlightReplay(const Config& config, BusNode& node, const int64_t& now_ts);
  // A recorded FLIGHT_SETPOINT: publishes the bridge's setpoint for the same instant.
  void on_recorded_setpoint(const void* data, size_t size);

 private:
  BusNode& node_;
  const int64_t& now_ts_;
  FlightBridge bridge_;
  OperatorState operator_;
  BridgeInputs in_;
  std::deque<std::pair<int64_t, std::function<void()>>> pending_;  // inputs by log time, not yet applied

  void later(std::function<void()> apply) { pending_.emplace_back(now_ts_, std::move(apply)); }
};

}  // namespace gpilot
