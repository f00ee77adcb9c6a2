// The vehicle's last line when gpilot-flight goes quiet (frozen, killed, its computer gone) is the autopilot's
// own offboard-loss failsafe: PX4 leaves OFFBOARD after COM_OF_LOSS_T seconds without a setpoint, ArduPilot
// stops in GUIDED after GUID_TIMEOUT. gpilot-flight reads that parameter (PARAM_REQUEST_READ) on every ENGAGE
// and engages only when the autopilot answers with a time no longer than flight.max_autopilot_loss_s.
// EngageGate is that exchange without a socket or a clock: times in, what to do out.
#pragma once

#include <cstdint>
#include <string>

#include "messages.hpp"

namespace gpilot::mavlink {

// The offboard-loss parameter of an autopilot ("px4": COM_OF_LOSS_T, "ardupilot": GUID_TIMEOUT).
std::string offboard_loss_param(const std::string& autopilot);

// "" when the answer allows engaging, else why not (naming the parameter and the limit).
std::string judge_offboard_loss(const ParamValue& answer, double max_s);

class EngageGate {
 public:
  // param: what to read; max_s: the longest acceptable failsafe time; timeout_s: how long to wait for the
  // answer (the request is sent again every timeout_s / 4 against a lost datagram).
  EngageGate(std::string param, double max_s, double timeout_s);

  enum class Action {
    None,     //!< nothing to do
    Request,  //!< send PARAM_REQUEST_READ for param() now
    Engage,   //!< the answer allows it: engage
    Refuse,   //!< refuse the ENGAGE: why()
  };
  // An ENGAGE arrived: Request (a check starts) or None (one is already running).
  Action engage_requested(int64_t now_utime);
  // Any other operator request (disengage, land ...) drops a pending ENGAGE.
  void cancel() { pending_ = false; }
  // A PARAM_VALUE arrived: Engage or Refuse when it answers a pending check, else None.
  Action on_param_value(const ParamValue& v);
  // Time passes: Request (resend), Refuse (no answer within timeout_s) or None.
  Action on_time(int64_t now_utime);

  bool pending() const { return pending_; }
  const std::string& param() const { return param_; }
  const std::string& why() const { return why_; }
  double last_value() const { return last_value_; }

 private:
  std::string param_;
  double max_s_, timeout_s_;
  bool pending_ = false;
  int64_t started_ = 0, last_sent_ = 0;
  std::string why_;
  double last_value_ = -1;
};

}  // namespace gpilot::mavlink
