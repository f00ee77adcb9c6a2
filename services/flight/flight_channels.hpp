// What gpilot-flight reads and writes, declared once (common/channel.hpp): its adapter, gpilot-replay, the
// view, gpilot-health --channels and DEVELOPERS.md's table read these.
#pragma once

#include "channel.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"

namespace gpilot {
namespace flight_channels {

constexpr Channel<gesture_cmd_t> kGestureCmd{"GESTURE_CMD"};
constexpr Channel<user_track_t> kUserTrack{"USER_TRACK"};
constexpr Channel<flight_control_t> kFlightControl{"FLIGHT_CONTROL"};  //!< from an operator (gpilot-ctl, view, launch)
constexpr Channel<flight_setpoint_t> kFlightSetpoint{"FLIGHT_SETPOINT"};
// Written from the simulator or the MAVLink vehicle; read with flight.backend none, where another process (or
// in replay the log) stands for the vehicle.
constexpr Channel<vehicle_state_t> kVehicleState{"VEHICLE_STATE"};

constexpr ChannelUse kUses[] = {kGestureCmd.in(),     kUserTrack.in(),     kFlightControl.in(),
                                kVehicleState.in(),   kFlightSetpoint.out(), kVehicleState.out()};

}  // namespace flight_channels
}  // namespace gpilot
