// The LCM channel names of ARCHITECTURE.md, for the tools that read whole runs (gpilot-view, gpilot-report).
#pragma once

namespace gpilot {
namespace channel {

constexpr const char* kCamera = "CAMERA";
constexpr const char* kTrackerInit = "TRACKER_INIT";
constexpr const char* kUserTrack = "USER_TRACK";
constexpr const char* kHandObs = "HAND_OBS";
constexpr const char* kGestureCmd = "GESTURE_CMD";
constexpr const char* kFlightControl = "FLIGHT_CONTROL";
constexpr const char* kFlightSetpoint = "FLIGHT_SETPOINT";
constexpr const char* kVehicleState = "VEHICLE_STATE";
constexpr const char* kGroundTruth = "GROUND_TRUTH";
constexpr const char* kHealth = "HEALTH";

}  // namespace channel
}  // namespace gpilot
