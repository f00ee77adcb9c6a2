// The operator's requests (FLIGHT_CONTROL) as the flight bridge sees them: engage, disengage, land set the
// bridge's engaged/landing inputs; arm, disarm, take-off are passed on to the vehicle. Each request is acted
// on once (gpilot-ctl repeats it against multicast loss). Shared by gpilot-flight and gpilot-replay.
#pragma once

#include <cstdint>
#include <string>

#include "flight_bridge.hpp"

namespace gpilot {

// Values equal flight_control_t::COMMAND_* (the adapter checks this at compile time).
enum class OperatorCommand : int8_t { Engage = 1, Disengage = 2, Arm = 3, Takeoff = 4, Land = 5, Disarm = 6 };

struct OperatorRequest {
  int64_t utime = 0;
  int64_t seq = 0;
  std::string source;
  int8_t command = 0;           //!< an OperatorCommand
  double takeoff_altitude = 0;  //!< m, for Takeoff
};

// What the vehicle itself must be told after a request (the backend's job).
enum class VehicleAction { None, Arm, Disarm, Takeoff, Land };

class OperatorState {
 public:
  // Applies a request to the bridge inputs. Returns the vehicle action, or None for a repeat or a request
  // that only changes the inputs. *why is set for a request that is refused (take-off without a height).
  VehicleAction apply(const OperatorRequest& r, BridgeInputs& in, std::string* why);
  bool repeat(const OperatorRequest& r) const;

 private:
  int64_t last_utime_ = -1, last_seq_ = -1;
  std::string last_source_;
};

}  // namespace gpilot
