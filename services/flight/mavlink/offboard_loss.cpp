#include "offboard_loss.hpp"

#include <cmath>
#include <cstdio>

namespace gpilot::mavlink {

std::string offboard_loss_param(const std::string& autopilot) {
  return autopilot == "ardupilot" ? "GUID_TIMEOUT" : "COM_OF_LOSS_T";
}

std::string judge_offboard_loss(const ParamValue& answer, double max_s) {
  const std::string name = param_name(answer.param_id);
  char buf[256];
  if (answer.param_type != kMavParamTypeReal32 || !std::isfinite(answer.param_value) || answer.param_value < 0) {
    std::snprintf(buf, sizeof buf, "the autopilot's %s is not a time in seconds (type %d, value %g)", name.c_str(),
                  answer.param_type, static_cast<double>(answer.param_value));
    return buf;
  }
  if (answer.param_value > max_s) {
    std::snprintf(buf, sizeof buf,
                  "the autopilot's %s is %.2f s, above flight.max_autopilot_loss_s %.2f s: it would fly on that "
                  "long after gpilot-flight stops (set %s <= %.2f on the autopilot)",
                  name.c_str(), static_cast<double>(answer.param_value), max_s, name.c_str(), max_s);
    return buf;
  }
  return "";
}

EngageGate::EngageGate(std::string param, double max_s, double timeout_s)
    : param_(std::move(param)), max_s_(max_s), timeout_s_(timeout_s) {}

EngageGate::Action EngageGate::engage_requested(int64_t now_utime) {
  if (pending_) return Action::None;
  pending_ = true;
  started_ = last_sent_ = now_utime;
  why_.clear();
  return Action::Request;
}

EngageGate::Action EngageGate::on_param_value(const ParamValue& v) {
  if (!pending_ || param_name(v.param_id) != param_) return Action::None;
  pending_ = false;
  last_value_ = v.param_value;
  why_ = judge_offboard_loss(v, max_s_);
  return why_.empty() ? Action::Engage : Action::Refuse;
}

EngageGate::Action EngageGate::on_time(int64_t now_utime) {
  if (!pending_) return Action::None;
  if (now_utime - started_ > static_cast<int64_t>(timeout_s_ * 1e6)) {
    pending_ = false;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "the autopilot did not answer PARAM_REQUEST_READ %s within %.2f s: its offboard-loss failsafe "
                  "time is unknown",
                  param_.c_str(), timeout_s_);
    why_ = buf;
    return Action::Refuse;
  }
  if (now_utime - last_sent_ >= static_cast<int64_t>(timeout_s_ / 4 * 1e6)) {
    last_sent_ = now_utime;
    return Action::Request;
  }
  return Action::None;
}

}  // namespace gpilot::mavlink
