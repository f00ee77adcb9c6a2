// What gpilot-flight reads and writes, declared once (common/channel.hpp): its adapter, gpilot-replay, the
// view, gpilot-health --channels and DEVELOPERS.md's table read these.
#pragma once

#include "channel.hpp"
#include "gpilot/autopilot_t.hpp"
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
// What the autopilot said (HEARTBEAT, PARAM_VALUE), written with backend mavlink as it arrives; read in replay,
// where the log stands for the autopilot: the engage gate and the link watch decide from these messages.
constexpr Channel<autopilot_t> kAutopilot{"AUTOPILOT"};

constexpr ChannelUse kUses[] = {kGestureCmd.in(),    kUserTrack.in(),       kFlightControl.in(),
                                kVehicleState.in(),  kAutopilot.in(),       kFlightSetpoint.out(),
                                kVehicleState.out(), kAutopilot.out()};

}  // namespace flight_channels
}  // namespace gpilot
