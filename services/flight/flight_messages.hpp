// LCM messages <-> the flight core's types, for gpilot-flight and gpilot-replay (the core has no LCM).
#pragma once

#include "flight_types.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"
#include "operator_state.hpp"

namespace gpilot {

GestureCommand to_core(const gesture_cmd_t& m);
UserTrack to_core(const user_track_t& m);
VehicleState to_core(const vehicle_state_t& m);
OperatorRequest to_core(const flight_control_t& m);
vehicle_state_t to_message(const VehicleState& v, int8_t source);
flight_setpoint_t to_message(const Setpoint& s);

}  // namespace gpilot
