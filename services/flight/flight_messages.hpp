// LCM messages <-> the flight core's types, for gpilot-flight and gpilot-replay (the core has no LCM).
#pragma once

#include "autopilot_watch.hpp"
#include "flight_types.hpp"
#include "gpilot/autopilot_t.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"
#include "mavlink/messages.hpp"
#include "operator_state.hpp"

namespace gpilot {

GestureCommand to_core(const gesture_cmd_t& m);
UserTrack to_core(const user_track_t& m);
VehicleState to_core(const vehicle_state_t& m);
OperatorRequest to_core(const flight_control_t& m);
vehicle_state_t to_message(const VehicleState& v, int8_t source);
flight_setpoint_t to_message(const Setpoint& s);
AutopilotMessage to_core(const autopilot_t& m);
// The autopilot's HEARTBEAT / PARAM_VALUE as AUTOPILOT carries it, received at utime (seq is the caller's).
autopilot_t to_message(const mavlink::Heartbeat& h, int64_t utime);
autopilot_t to_message(const mavlink::ParamValue& v, int64_t utime);

}  // namespace gpilot
