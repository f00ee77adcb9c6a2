#include "analyze_log.hpp"

#include <memory>

#include "channels.hpp"
#include "log_reader.hpp"

namespace gpilot {

LogAnalysis analyse_log(const std::string& path, const Settling& settling, const std::string& progress_tool) {
  LogReader log(path);
  LogDispatcher d;
  RunAnalyzer a(settling);
  d.on<image_t>(channel::kCamera, [&](const image_t& m, int64_t t) { a.on_camera(m, t); });
  d.on<user_track_t>(channel::kUserTrack, [&](const user_track_t& m, int64_t t) { a.on_track(m, t); });
  d.on<gesture_cmd_t>(channel::kGestureCmd, [&](const gesture_cmd_t& m, int64_t t) { a.on_command(m, t); });
  d.on<flight_setpoint_t>(channel::kFlightSetpoint, [&](const flight_setpoint_t& m, int64_t t) { a.on_setpoint(m, t); });
  d.on<vehicle_state_t>(channel::kVehicleState, [&](const vehicle_state_t& m, int64_t t) { a.on_vehicle(m, t); });
  d.on<ground_truth_t>(channel::kGroundTruth, [&](const ground_truth_t& m, int64_t t) { a.on_truth(m, t); });
  d.on<health_t>(channel::kHealth, [&](const health_t& m, int64_t t) { a.on_health(m, t); });
  d.on<hand_obs_t>(channel::kHandObs, [&](const hand_obs_t& m, int64_t t) { a.on_hands(m, t); });

  std::unique_ptr<Progress> progress;
  if (!progress_tool.empty()) progress = std::make_unique<Progress>(progress_tool);
  LogEvent ev;
  while (log.next(ev)) {
    d.dispatch(ev);
    if (progress) progress->update(log, "reading");
  }
  LogAnalysis out;
  out.summary = a.summary();
  out.path = a.trajectory();
  out.events = log.events_read();
  out.warnings = log.warnings();
  if (d.rejected_total() > 0)
    out.warnings.push_back(std::to_string(d.rejected_total()) + " messages did not decode or were invalid (last: " +
                           d.last_reject_reason() + ")");
  out.rejected = d.rejected_by_channel();
  if (out.summary.logger_lost() > 0) {
    std::string which;
    for (const auto& [channel, g] : out.summary.gaps)
      if (g.counter && g.missing > 0) which += (which.empty() ? "" : ", ") + channel + " " + std::to_string(g.missing);
    out.warnings.push_back("the logger lost " + std::to_string(out.summary.logger_lost()) +
                           " messages (gaps in seq: " + which + "); see log_gaps in summary.json");
  }
  return out;
}

}  // namespace gpilot
