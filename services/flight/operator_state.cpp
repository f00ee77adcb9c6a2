// Operator requests to bridge inputs and vehicle actions (see operator_state.hpp).
#include "operator_state.hpp"

namespace gpilot {

bool OperatorState::repeat(const OperatorRequest& r) const {
  return r.utime == last_utime_ && r.seq == last_seq_ && r.source == last_source_;
}

VehicleAction OperatorState::apply(const OperatorRequest& r, BridgeInputs& in, std::string* why) {
  if (repeat(r)) return VehicleAction::None;
  last_utime_ = r.utime;
  last_seq_ = r.seq;
  last_source_ = r.source;
  switch (static_cast<OperatorCommand>(r.command)) {
    case OperatorCommand::Engage:
      in.engaged = true;
      in.landing = false;
      return VehicleAction::None;
    case OperatorCommand::Disengage: in.engaged = false; return VehicleAction::None;
    case OperatorCommand::Land:
      in.engaged = false;
      in.landing = true;
      return VehicleAction::Land;
    case OperatorCommand::Arm: return VehicleAction::Arm;
    case OperatorCommand::Disarm: return VehicleAction::Disarm;
    case OperatorCommand::Takeoff:
      if (!(r.takeoff_altitude > 0.0)) {
        if (why) *why = "FLIGHT_CONTROL: TAKEOFF needs a positive takeoff_altitude";
        return VehicleAction::None;
      }
      in.landing = false;
      return VehicleAction::Takeoff;
  }
  return VehicleAction::None;
}

}  // namespace gpilot
