// The LCM channel names for the tools that read whole runs (gpilot-view, gpilot-report): the names the stages
// declare (services/<stage>/<stage>_channels.hpp, common/process_channels.hpp), not a copy of them.
#pragma once

#include "capture/capture_channels.hpp"
#include "decide/decide_channels.hpp"
#include "flight/flight_channels.hpp"
#include "hands/hands_channels.hpp"
#include "process_channels.hpp"
#include "tracker/tracker_channels.hpp"

namespace gpilot {
namespace channel {

constexpr const char* kCamera = capture_channels::kCamera.name;
constexpr const char* kTrackerInit = tracker_channels::kTrackerInit.name;
constexpr const char* kUserTrack = tracker_channels::kUserTrack.name;
constexpr const char* kHandObs = hands_channels::kHandObs.name;
constexpr const char* kGestureCmd = decide_channels::kGestureCmd.name;
constexpr const char* kFlightControl = flight_channels::kFlightControl.name;
constexpr const char* kFlightSetpoint = flight_channels::kFlightSetpoint.name;
constexpr const char* kVehicleState = flight_channels::kVehicleState.name;
constexpr const char* kGroundTruth = capture_channels::kGroundTruth.name;
constexpr const char* kHealth = process_channels::kHealth.name;

}  // namespace channel
}  // namespace gpilot
