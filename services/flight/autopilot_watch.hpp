// AutopilotWatch: what gpilot-flight concludes from what the autopilot said (AUTOPILOT messages), without a
// socket or a clock: the ENGAGE gate (the offboard-loss parameter's answer, or none within
// mavlink.param_timeout_s) and the link (the autopilot's HEARTBEAT, lost after mavlink.link_timeout_s). The
// service feeds it the AUTOPILOT messages it publishes (live) or reads from the log (replay) and calls tick()
// at each setpoint tick: every decision is taken at a tick, on the tick's time, from the messages that tick
// had, so a replay on the log's ticks decides exactly as the live run did.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mavlink/offboard_loss.hpp"

namespace gpilot {

// One message from the autopilot, as AUTOPILOT carries it (flight_messages.hpp converts).
struct AutopilotMessage {
  enum class Kind { Heartbeat, ParamValue };
  Kind kind = Kind::Heartbeat;
  bool armed = false;                 //!< HEARTBEAT
  int base_mode = 0;                  //!< HEARTBEAT: MAV_MODE_FLAG bits
  int64_t custom_mode = 0;            //!< HEARTBEAT: the autopilot's own mode number
  int system_status = 0;              //!< HEARTBEAT: MAV_STATE
  std::string param_id;               //!< PARAM_VALUE
  float param_value = 0;              //!< PARAM_VALUE
  int param_type = 0;                 //!< PARAM_VALUE: MAV_PARAM_TYPE
};

class AutopilotWatch {
 public:
  // param: the offboard-loss parameter (mavlink::offboard_loss_param); max_loss_s: the longest acceptable
  // failsafe time; param_timeout_s: how long ENGAGE waits for its answer; link_timeout_s: how long without
  // the autopilot's HEARTBEAT before the link counts as lost.
  AutopilotWatch(std::string param, double max_loss_s, double param_timeout_s, double link_timeout_s);

  // An ENGAGE arrived: the check starts at the next tick.
  void engage_requested() { engage_waiting_ = true; }
  // Any other operator request drops a pending ENGAGE.
  void cancel();
  // A message from the autopilot: taken at the next tick.
  void heard(const AutopilotMessage& m) { heard_.push_back(m); }

  // What a tick decided. At most one of engage / refuse; link_lost means disengage.
  struct Decision {
    bool request_param = false;  //!< send PARAM_REQUEST_READ of param() now
    bool engage = false;         //!< the answer allows the pending ENGAGE
    std::string refuse;          //!< the pending ENGAGE is refused, and why
    std::string link_lost;       //!< the link was up and is lost now, and why: disengage
    bool link_back = false;      //!< the autopilot is heard again after a loss
  };
  Decision tick(int64_t now_utime);

  bool link_up() const { return link_up_; }
  bool ever_heard() const { return last_heard_ >= 0; }
  int64_t last_heard() const { return last_heard_; }  //!< the tick that had its last message; -1 if none
  bool armed() const { return armed_; }
  const std::string& param() const { return gate_.param(); }
  double last_value() const { return gate_.last_value(); }
  bool pending() const { return engage_waiting_ || gate_.pending(); }

 private:
  mavlink::EngageGate gate_;
  int64_t link_timeout_us_;
  bool engage_waiting_ = false;  // an ENGAGE since the last tick
  std::vector<AutopilotMessage> heard_;
  bool link_up_ = false, lost_ = false, armed_ = false;
  int64_t last_heard_ = -1;
};

}  // namespace gpilot
