#include "autopilot_watch.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace gpilot {

AutopilotWatch::AutopilotWatch(std::string param, double max_loss_s, double param_timeout_s, double link_timeout_s)
    : gate_(std::move(param), max_loss_s, param_timeout_s),
      link_timeout_us_(static_cast<int64_t>(link_timeout_s * 1e6)) {}

void AutopilotWatch::cancel() {
  engage_waiting_ = false;
  gate_.cancel();
}

AutopilotWatch::Decision AutopilotWatch::tick(int64_t now_utime) {
  using A = mavlink::EngageGate::Action;
  Decision d;
  const auto act = [&](A a) {
    if (a == A::Request) d.request_param = true;
    if (a == A::Engage) d.engage = true;
    if (a == A::Refuse) d.refuse = gate_.why();
  };
  // What the autopilot said since the last tick: any message of it is the link alive.
  for (const AutopilotMessage& m : heard_) {
    last_heard_ = now_utime;
    if (!link_up_ && lost_) d.link_back = true;
    link_up_ = true;
    if (m.kind == AutopilotMessage::Kind::Heartbeat) armed_ = m.armed;
    if (m.kind == AutopilotMessage::Kind::ParamValue) {
      mavlink::ParamValue v;
      std::memcpy(v.param_id, m.param_id.data(), std::min(m.param_id.size(), sizeof v.param_id));  // 16: unterminated
      v.param_value = m.param_value;
      v.param_type = static_cast<uint8_t>(m.param_type);
      if (!d.engage && d.refuse.empty()) act(gate_.on_param_value(v));
    }
  }
  heard_.clear();
  if (link_up_ && now_utime - last_heard_ > link_timeout_us_) {
    link_up_ = false;
    lost_ = true;
    char buf[160];
    std::snprintf(buf, sizeof buf, "the autopilot's link is lost: nothing heard from it for %.2f s",
                  static_cast<double>(now_utime - last_heard_) * 1e-6);
    d.link_lost = buf;
    d.link_back = false;
    if (gate_.pending()) {
      gate_.cancel();
      d.refuse = d.link_lost;
    }
  }
  if (d.engage || !d.refuse.empty()) return d;
  act(gate_.on_time(now_utime));
  // A new ENGAGE starts its check on this tick's time (one already running goes on).
  if (engage_waiting_ && d.refuse.empty()) act(gate_.engage_requested(now_utime));
  engage_waiting_ = false;
  return d;
}

}  // namespace gpilot
