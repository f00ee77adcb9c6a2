// The flight stage in a replay: the bridge (the same FlightBridge and OperatorState as gpilot-flight) fed the
// logged GESTURE_CMD, USER_TRACK, VEHICLE_STATE and FLIGHT_CONTROL with their log times as receipt times, and
// asked for a setpoint at each recorded FLIGHT_SETPOINT's own time, from the command and track that setpoint
// says it saw, with the arrival times it says they had (the logger may write an input before a setpoint the
// bridge computed just before that input reached it, and its clock reads a millisecond apart). Vehicle states come from the flight process itself, so their
// order in the log is the bridge's. The vehicle is not simulated again: this replays the decisions (zeroing,
// spacing, limits, yaw), not the flight.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

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
  // Commands and tracks in log order, with their log times, not yet given to the bridge.
  std::deque<std::pair<int64_t, GestureCommand>> commands_;
  std::deque<std::pair<int64_t, UserTrack>> tracks_;
};

}  // namespace gpilot
