#include "run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "box_iou.hpp"
#include "overlay.hpp"
#include "stage_stats.hpp"

namespace gpilot {
namespace {

LatencyStats latency(std::vector<int64_t> us) {
  LatencyStats s;
  s.n = static_cast<int64_t>(us.size());
  if (us.empty()) return s;
  s.median_ms = quantile(us, 0.5) / 1000.0;
  s.p95_ms = quantile(us, 0.95) / 1000.0;
  return s;
}

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::vector<int64_t> scaled;  // quantile() is over integers: work in microunits
  for (double x : v) scaled.push_back(static_cast<int64_t>(std::llround(x * 1e6)));
  return quantile(scaled, 0.5) / 1e6;
}

const char* health_state_name(int s) {
  switch (s) {
    case health_t::STATE_STARTING: return "STARTING";
    case health_t::STATE_OK: return "OK";
    case health_t::STATE_DEGRADED: return "DEGRADED";
    case health_t::STATE_ERROR: return "ERROR";
    case health_t::STATE_STOPPING: return "STOPPING";
    default: return "?";
  }
}

bool valid_mode(int m) { return m >= 0 && m < kModes; }

// The JSON's numbers: six significant digits, as the summary has always written them ("%.6g"); a
// non-finite number as null. The double parsed back from those digits dumps as the same digits.
json sig6(double v) {
  if (!std::isfinite(v)) return nullptr;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return std::strtod(buf, nullptr);
}

json latency_json(const LatencyStats& l) {
  return {{"n", l.n}, {"median", l.n ? sig6(l.median_ms) : json(nullptr)}, {"p95", l.n ? sig6(l.p95_ms) : json(nullptr)}};
}

}  // namespace

void TrackVsTruth::add(int status, double iou) {
  ++frames;
  if (status != user_track_t::STATUS_TRACKING) return;
  ++tracking;
  on_user += iou >= 0.5;
  elsewhere += iou < 0.2;
  iou_sum += iou;
  iou_min = std::min(iou_min, iou);
}

Settling settling_for(const std::string& rule, int buffer_size) {
  Settling s;
  if (rule == "paper") {
    s.frames = std::max(1, buffer_size) / 2 + 1;
    s.why = std::to_string(s.frames) + " frames (decide.rule paper: decide.buffer_size / 2 + 1, buffer_size " +
            std::to_string(std::max(1, buffer_size)) + ")";
  } else {
    s.seconds = ScoreRules{}.judged_after_s;
    char b[96];
    std::snprintf(b, sizeof b, "%.1f s (decide.rule %s, as the e2e tests judge)", s.seconds, rule.c_str());
    s.why = b;
  }
  return s;
}

RunAnalyzer::RunAnalyzer(Settling settling) : settling_(std::move(settling)) {}

int64_t Summary::logger_lost() const {
  int64_t n = 0;
  for (const auto& [channel, g] : gaps)
    if (g.counter) n += g.missing;
  return n;
}

void RunAnalyzer::note_seq(const std::string& channel, bool counter, const std::string& publisher, int64_t seq) {
  ChannelGaps& g = gaps_[channel];
  g.counter = counter;
  ++g.messages;
  const auto key = std::make_pair(channel, publisher);
  const auto it = last_seq_.find(key);
  if (it == last_seq_.end() || seq <= it->second) {
    ++g.streams;  // the first message, or a restarted publisher (its seq starts again)
  } else if (seq > it->second + 1) {
    g.missing += seq - it->second - 1;
  }
  last_seq_[key] = seq;
}

void RunAnalyzer::on_hands(const hand_obs_t& m, int64_t) { note_seq("HAND_OBS", false, "", m.seq); }

void RunAnalyzer::on_camera(const image_t& m, int64_t recv_utime) {
  if (frames_ == 0) first_frame_utime_ = m.utime;
  last_frame_utime_ = std::max(last_frame_utime_, m.utime);
  ++frames_;
  frames_by_seq_[m.seq] = FrameTimes{m.utime, recv_utime};
  note_seq("CAMERA", true, "", m.seq);
}

void RunAnalyzer::on_track(const user_track_t& m, int64_t) {
  ++track_frames_;
  note_seq("USER_TRACK", false, "", m.seq);
  if (m.status >= 0 && m.status < 3) ++track_by_status_[static_cast<size_t>(m.status)];
  if (m.status == user_track_t::STATUS_TRACKING && m.facing == user_track_t::FACING_AWAY) ++track_turned_away_;
  track_box_by_seq_[m.seq] = {m.status, {m.box[0], m.box[1], m.box[2], m.box[3]}, m.image_width, m.image_height};
}

void RunAnalyzer::on_command(const gesture_cmd_t& m, int64_t recv_utime) {
  ++commands_;
  note_seq("GESTURE_CMD", false, "", m.seq);
  if (valid_mode(m.mode)) ++commands_by_mode_[static_cast<size_t>(m.mode)];
  command_mode_by_seq_[m.seq] = m.mode;
  command_by_seq_[m.seq] = {m.mode, {m.direction[0], m.direction[1]}};
  current_mode_ = m.mode;
  const auto f = frames_by_seq_.find(m.seq);
  if (f == frames_by_seq_.end()) {
    ++unmatched_;
    return;
  }
  lat_cmd_.push_back(recv_utime - f->second.utime);
  pipe_cmd_.push_back(recv_utime - f->second.recv);
}

void RunAnalyzer::on_setpoint(const flight_setpoint_t& m, int64_t recv_utime) {
  Engagement& e = engagement_;
  e.disengagements += e.engaged_at_end && !m.engaged;
  ++e.setpoints;
  e.engaged_setpoints += m.engaged;
  e.engaged_at_end = m.engaged;
  if (m.seq < 0 || setpoint_seen_.count(m.seq)) return;  // the first setpoint that follows each frame
  setpoint_seen_[m.seq] = true;
  const auto f = frames_by_seq_.find(m.seq);
  if (f == frames_by_seq_.end()) return;
  lat_sp_.push_back(recv_utime - f->second.utime);
  pipe_sp_.push_back(recv_utime - f->second.recv);
}

void RunAnalyzer::on_vehicle(const vehicle_state_t& m, int64_t recv_utime) {
  if (first_vehicle_recv_ < 0) first_vehicle_recv_ = recv_utime;
  note_seq("VEHICLE_STATE", true, std::to_string(m.source), m.seq);
  TrajectoryPoint p{};
  p.t_s = (recv_utime - first_vehicle_recv_) * 1e-6;
  p.north = m.position[0];
  p.east = m.position[1];
  p.down = m.position[2];
  p.yaw = m.attitude[2];
  p.mode = current_mode_;
  p.has_person = has_person_;
  p.person_north = person_n_;
  p.person_east = person_e_;
  path_.push_back(p);
}

void RunAnalyzer::on_truth(const ground_truth_t& m, int64_t) {
  note_seq("GROUND_TRUTH", true, "", m.seq);
  truth_by_seq_[m.seq] = {m.utime, m.gesture, m.expected_mode, {m.expected_direction[0], m.expected_direction[1]}};
  truth_box_by_seq_[m.seq] = {{m.user_box[0], m.user_box[1], m.user_box[2], m.user_box[3]},
                              std::hypot(m.person_position[0] - m.camera_position[0], m.person_position[1] - m.camera_position[1])};
  has_person_ = true;
  person_n_ = m.person_position[0];
  person_e_ = m.person_position[1];
}

void RunAnalyzer::on_health(const health_t& m, int64_t) {
  health_[m.name].push_back(m);
  if (m.name == "gpilot-flight")
    for (const std::string& said : {m.state_detail, m.last_reject_reason})
      if (said.rfind("refusing to engage", 0) == 0 || said.rfind("disengaged", 0) == 0) engagement_.last_refusal = said;
  note_seq("HEALTH", true, m.name + " " + std::to_string(m.pid), m.seq);
}

Summary RunAnalyzer::summary() const {
  Summary s;
  s.frames = frames_;
  s.duration_s = frames_ > 1 ? (last_frame_utime_ - first_frame_utime_) * 1e-6 : 0.0;
  s.camera_hz = s.duration_s > 0 ? (frames_ - 1) / s.duration_s : 0.0;
  s.commands_by_mode = commands_by_mode_;
  s.commands = commands_;
  s.track_frames = track_frames_;
  s.track_by_status = track_by_status_;
  s.track_turned_away = track_turned_away_;
  s.latency_cmd = latency(lat_cmd_);
  s.latency_setpoint = latency(lat_sp_);
  s.pipeline_cmd = latency(pipe_cmd_);
  s.pipeline_setpoint = latency(pipe_sp_);
  s.unmatched_commands = unmatched_;
  s.engagement = engagement_;

  for (const auto& [name, reports] : health_) {
    StageHealth h;
    h.name = name;
    h.reports = static_cast<int64_t>(reports.size());
    std::vector<double> rates, p50, p99;
    for (const auto& r : reports) {
      if (r.seq > 0) rates.push_back(r.rate_out_hz);
      if (r.processing_ms_p50 > 0 || r.processing_ms_p99 > 0) {
        p50.push_back(r.processing_ms_p50);
        p99.push_back(r.processing_ms_p99);
        h.processing_p99_max_ms = std::max<double>(h.processing_p99_max_ms, r.processing_ms_p99);
      }
    }
    // CPU: a restart (a new pid) starts from zero again, so each pid's reports are a window of their own.
    double cpu_s = 0, wall_s = 0;
    int64_t window_frames = 0;
    for (size_t i = 0; i < reports.size();) {
      size_t j = i;
      while (j + 1 < reports.size() && reports[j + 1].pid == reports[i].pid) ++j;
      if (j > i && reports[j].cpu_s >= reports[i].cpu_s) {
        cpu_s += reports[j].cpu_s - reports[i].cpu_s;
        wall_s += (reports[j].utime - reports[i].utime) * 1e-6;
        for (const auto& [seq, f] : frames_by_seq_)
          window_frames += f.recv >= reports[i].utime && f.recv <= reports[j].utime;
      }
      i = j + 1;
    }
    if (window_frames > 0) h.cpu_ms_per_frame = 1e3 * cpu_s / static_cast<double>(window_frames);
    if (wall_s > 0) h.cpu_percent = 100 * cpu_s / wall_s;
    const health_t& last = reports.back();
    h.rate_out_last_hz = last.rate_out_hz;
    h.rate_out_median_hz = median_of(rates);
    h.processing_p50_ms = median_of(p50);
    h.processing_p99_ms = median_of(p99);
    h.messages_in = last.messages_in;
    h.messages_out = last.messages_out;
    h.rejected = last.rejected;
    h.dropped = last.dropped;
    h.last_state = last.state;
    h.last_reject_reason = last.last_reject_reason;
    s.stages.push_back(h);
  }

  // Accuracy: a frame counts once the rule deciding could have reacted to the expected gesture (Settling).
  Accuracy& a = s.accuracy;
  a.settle_frames = settling_.frames;
  a.settle_s = settling_.seconds;
  a.rule = "frames with a GESTURE_CMD and a GROUND_TRUTH of the same seq, expected_mode == mode; the first " +
           settling_.why + " from the start and from each change of GROUND_TRUTH.expected_mode are not counted";
  for (size_t b = 0; b < kRangeBandEdges.size(); ++b)
    s.range_bands.push_back({kRangeBandEdges[b], b + 1 < kRangeBandEdges.size() ? kRangeBandEdges[b + 1] : INFINITY, 0, 0, 0, {}});
  const auto band_of = [&s](int64_t seq, const std::map<int64_t, TruthBox>& boxes) -> RangeBand* {
    const auto t = boxes.find(seq);
    if (t == boxes.end()) return nullptr;
    for (auto& b : s.range_bands)
      if (t->second.range_m >= b.from_m && t->second.range_m < b.to_m) return &b;
    return nullptr;
  };
  for (const auto& [seq, truth] : truth_box_by_seq_) {
    RangeBand* band = band_of(seq, truth_box_by_seq_);
    if (band) ++band->truth_frames;
    const auto tr = track_box_by_seq_.find(seq);
    if (tr == track_box_by_seq_.end() || !(truth.box[2] > 0 && truth.box[3] > 0)) continue;
    const double cx = truth.box[0] + 0.5 * truth.box[2], cy = truth.box[1] + 0.5 * truth.box[3];
    if (cx < 0 || cy < 0 || cx >= tr->second.width || cy >= tr->second.height) continue;  // the user is out of view
    const auto& t = tr->second.box;
    const double v = iou(cv::Rect2d(t[0], t[1], t[2], t[3]), cv::Rect2d(truth.box[0], truth.box[1], truth.box[2], truth.box[3]));
    s.track_vs_truth.add(tr->second.status, v);
    if (band) band->track.add(tr->second.status, v);
  }
  int prev = -1;
  int64_t change_seq = 0, change_utime = 0;
  bool first = true;
  for (const auto& [seq, truth] : truth_by_seq_) {
    ++a.truth_frames;
    const int expected = truth.expected_mode;
    if (first || expected != prev) change_seq = seq, change_utime = truth.utime;
    first = false;
    prev = expected;
    const auto c = command_mode_by_seq_.find(seq);
    if (c == command_mode_by_seq_.end()) continue;
    ++a.frames_with_command;
    if (seq - change_seq < a.settle_frames || static_cast<double>(truth.utime - change_utime) < a.settle_s * 1e6) {
      ++a.skipped_settling;
      continue;
    }
    ++a.evaluated;
    if (c->second == expected) ++a.correct;
    if (RangeBand* band = band_of(seq, truth_box_by_seq_)) {
      ++band->evaluated;
      band->correct += c->second == expected;
    }
    if (valid_mode(expected) && valid_mode(c->second))
      ++a.confusion[static_cast<size_t>(expected)][static_cast<size_t>(c->second)];
  }

  s.gaps = gaps_;
  std::vector<TruthFrame> truth;
  std::vector<ScoredCommand> commands;
  for (const auto& [seq, t] : truth_by_seq_) {
    truth.push_back(t);
    const auto c = command_by_seq_.find(seq);
    commands.push_back(c == command_by_seq_.end() ? ScoredCommand{} : c->second);  // no command: HOVER
  }
  if (!truth.empty()) s.reaction = score_commands(truth, commands, ScoreRules{});

  s.vehicle_states = static_cast<int64_t>(path_.size());
  for (size_t i = 1; i < path_.size(); ++i)
    s.path_length_m += std::sqrt(std::pow(path_[i].north - path_[i - 1].north, 2) +
                                 std::pow(path_[i].east - path_[i - 1].east, 2) +
                                 std::pow(path_[i].down - path_[i - 1].down, 2));
  return s;
}

json summary_json(const Summary& s, const json& extra) {
  json j = json::object();
  for (const auto& [k, v] : extra.items()) j[k] = v;
  j["frames"] = s.frames;
  j["duration_s"] = sig6(s.duration_s);
  j["camera_hz"] = sig6(s.camera_hz);
  json by_mode = json::object();
  for (int m = 0; m < kModes; ++m) by_mode[mode_name(m)] = s.commands_by_mode[static_cast<size_t>(m)];
  j["commands"] = {{"total", s.commands}, {"by_mode", by_mode}};
  json track = {{"frames", s.track_frames}};
  for (int st = 0; st < 3; ++st) track[track_status_name(st)] = s.track_by_status[static_cast<size_t>(st)];
  track["TRACKING_turned_away"] = s.track_turned_away;
  j["track"] = track;
  json stages = json::object();
  for (const auto& h : s.stages)
    stages[h.name] = {{"reports", h.reports},
                      {"rate_out_hz_last", sig6(h.rate_out_last_hz)},
                      {"rate_out_hz_median", sig6(h.rate_out_median_hz)},
                      {"processing_ms_p50", sig6(h.processing_p50_ms)},
                      {"processing_ms_p99", sig6(h.processing_p99_ms)},
                      {"processing_ms_p99_max", sig6(h.processing_p99_max_ms)},
                      {"cpu_ms_per_frame", sig6(h.cpu_ms_per_frame)},
                      {"cpu_percent", sig6(h.cpu_percent)},
                      {"messages_in", h.messages_in},
                      {"messages_out", h.messages_out},
                      {"rejected", h.rejected},
                      {"dropped", h.dropped},
                      {"last_state", health_state_name(h.last_state)},
                      {"last_reject_reason", h.last_reject_reason}};
  j["stages"] = stages;
  j["latency_ms"] = {
      {"frame_to_gesture_cmd", latency_json(s.latency_cmd)},
      {"frame_to_flight_setpoint", latency_json(s.latency_setpoint)},
      {"camera_receipt_to_gesture_cmd", latency_json(s.pipeline_cmd)},
      {"camera_receipt_to_flight_setpoint", latency_json(s.pipeline_setpoint)},
      {"unmatched_commands", s.unmatched_commands},
      {"definition",
       "receipt time in the log minus the frame's utime (frame_to_*) or minus the CAMERA frame's receipt time "
       "(camera_receipt_to_*), matched by seq; FLIGHT_SETPOINT: the first one of each seq"}};
  const Accuracy& a = s.accuracy;
  json modes = json::array();
  for (int m = 0; m < kModes; ++m) modes.push_back(mode_name(m));
  j["gesture_accuracy"] = {{"accuracy", a.has_value() ? sig6(a.value()) : json(nullptr)},
                           {"accuracy_percent", a.has_value() ? sig6(100.0 * a.value()) : json(nullptr)},
                           {"correct", a.correct},
                           {"evaluated", a.evaluated},
                           {"truth_frames", a.truth_frames},
                           {"frames_with_command", a.frames_with_command},
                           {"skipped_settling", a.skipped_settling},
                           {"settle_frames", a.settle_frames},
                           {"settle_s", a.settle_s},
                           {"rule", a.rule},
                           {"confusion", {{"modes", modes}, {"rows_expected_columns_decided", a.confusion}}}};
  const auto track_json = [](const TrackVsTruth& t) {
    return json{{"frames", t.frames},
                {"tracking", t.tracking},
                {"on_user", t.on_user},
                {"on_user_percent", t.tracking ? sig6(100.0 * t.on_user / t.tracking) : json(nullptr)},
                {"elsewhere", t.elsewhere},
                {"mean_iou", t.tracking ? sig6(t.mean_iou()) : json(nullptr)},
                {"min_iou", t.tracking ? sig6(t.iou_min) : json(nullptr)}};
  };
  j["track_vs_truth"] = track_json(s.track_vs_truth);
  j["track_vs_truth"]["definition"] =
      "USER_TRACK.box against GROUND_TRUTH.user_box of the same seq, frames with the user in view; on_user: TRACKING "
      "with IoU >= 0.5; elsewhere: TRACKING with IoU < 0.2 (on a bystander or the background); IoU over TRACKING frames";
  json bands = json::array();
  for (const auto& b : s.range_bands) {
    if (b.truth_frames == 0) continue;
    bands.push_back({{"from_m", sig6(b.from_m)},
                     {"to_m", std::isfinite(b.to_m) ? sig6(b.to_m) : json(nullptr)},
                     {"truth_frames", b.truth_frames},
                     {"evaluated", b.evaluated},
                     {"correct", b.correct},
                     {"accuracy_percent", b.evaluated ? sig6(100.0 * b.correct / b.evaluated) : json(nullptr)},
                     {"track", track_json(b.track)}});
  }
  j["range_bands"] = {{"bands", bands},
                      {"definition",
                       "per band of the drone's horizontal range to the user (GROUND_TRUTH camera_position to "
                       "person_position; bands without frames left out): gesture_accuracy's frames and rule, and "
                       "track_vs_truth"}};
  const Score& r = s.reaction;
  j["gesture_reaction"] = {
      {"changes", r.changes},
      {"missed", r.missed},
      {"median_s", sig6(r.reaction_median_s())},
      {"max_s", sig6(r.reaction_max_s())},
      {"median_frames", r.reaction_median_frames()},
      {"max_frames", r.reaction_max_frames()},
      {"frames", r.frames},
      {"old_command_frames", r.old_frames},
      {"old_command_percent", sig6(r.frames ? 100.0 * r.old_frames / r.frames : 0.0)},
      {"wrong_frames", r.wrong_frames},
      {"false_at_rest", r.false_at_rest},
      {"confused", r.confused},
      {"definition",
       "every frame with GROUND_TRUTH, no settling skipped (gpilot-eval-decide's scoring): reaction from a true "
       "gesture change to the first GESTURE_CMD with the new command; old_command_frames: frames from each change to "
       "it; false_at_rest: a motion commanded while the user rests; confused: another motion than the one asked"}};
  j["vehicle"] = {{"states", s.vehicle_states}, {"path_length_m", sig6(s.path_length_m)}};
  const Engagement& e = s.engagement;
  j["flight"] = {{"engaged", e.engaged_setpoints > 0},
                 {"setpoints", e.setpoints},
                 {"engaged_setpoints", e.engaged_setpoints},
                 {"engaged_at_end", e.engaged_at_end},
                 {"disengagements", e.disengagements},
                 {"refused_or_lost", e.last_refusal},
                 {"definition",
                  "engaged: any FLIGHT_SETPOINT engaged; refused_or_lost: gpilot-flight's last refusal of an ENGAGE or "
                  "loss of the autopilot's link (its HEALTH), \"\" if none"}};
  json channels = json::object();
  for (const auto& [channel, g] : s.gaps)
    channels[channel] = {{"messages", g.messages},
                         {"missing", g.missing},
                         {"streams", g.streams},
                         {"a_gap_is", g.counter ? "lost by the logger"
                                                : "skipped by a stage (HEALTH.dropped) or lost by the logger"}};
  j["log_gaps"] = {{"logger_lost", s.logger_lost()},
                   {"channels", channels},
                   {"definition",
                    "per channel, seq values skipped inside each publisher's stream (a seq going back starts a new "
                    "stream); logger_lost sums the channels where every seq is one message sent (CAMERA, "
                    "GROUND_TRUTH, VEHICLE_STATE, HEALTH per process)"}};
  return j;
}

std::string summary_table(const Summary& s) {
  std::string t;
  char buf[256];
  auto line = [&](const char* f, auto... args) {
    std::snprintf(buf, sizeof buf, f, args...);
    t += buf;
  };
  line("frames            %lld over %.1f s (%.1f Hz)\n", static_cast<long long>(s.frames), s.duration_s, s.camera_hz);
  line("commands          %lld:", static_cast<long long>(s.commands));
  for (int m = 0; m < kModes; ++m) line(" %s %lld", mode_name(m), static_cast<long long>(s.commands_by_mode[static_cast<size_t>(m)]));
  t += "\n";
  line("track             %lld frames: TRACKING %lld (the user turned away on %lld), LOST %lld, SEARCHING %lld\n",
       static_cast<long long>(s.track_frames), static_cast<long long>(s.track_by_status[1]),
       static_cast<long long>(s.track_turned_away), static_cast<long long>(s.track_by_status[2]),
       static_cast<long long>(s.track_by_status[0]));
  auto lat = [&](const char* name, const LatencyStats& l) {
    if (l.n)
      line("%-34s %6lld %9.1f %9.1f\n", name, static_cast<long long>(l.n), l.median_ms, l.p95_ms);
    else
      line("%-34s %6d %9s %9s\n", name, 0, "-", "-");
  };
  line("\n%-34s %6s %9s %9s\n", "latency (ms)", "n", "median", "p95");
  lat("frame utime -> GESTURE_CMD", s.latency_cmd);
  lat("frame utime -> FLIGHT_SETPOINT", s.latency_setpoint);
  lat("CAMERA receipt -> GESTURE_CMD", s.pipeline_cmd);
  lat("CAMERA receipt -> FLIGHT_SETPOINT", s.pipeline_setpoint);
  line("\n%-18s %7s %9s %9s %9s %9s %11s %9s %9s %8s\n", "stage", "reports", "Hz last", "Hz med", "p50 ms", "p99 ms",
       "CPU ms/frm", "rejected", "dropped", "state");
  for (const auto& h : s.stages)
    line("%-18s %7lld %9.1f %9.1f %9.2f %9.2f %11.3f %9lld %9lld %8s\n", h.name.c_str(), static_cast<long long>(h.reports),
         h.rate_out_last_hz, h.rate_out_median_hz, h.processing_p50_ms, h.processing_p99_ms, h.cpu_ms_per_frame,
         static_cast<long long>(h.rejected), static_cast<long long>(h.dropped), health_state_name(h.last_state));
  line("\nnot in the log     %lld lost by the logger;", static_cast<long long>(s.logger_lost()));
  for (const auto& [channel, g] : s.gaps)
    line(" %s %lld/%lld%s", channel.c_str(), static_cast<long long>(g.missing),
         static_cast<long long>(g.messages + g.missing), g.counter ? "" : "*");
  t += s.gaps.empty() ? "\n" : "\n                   (* gaps there are also frames a stage skipped: see dropped)\n";
  const Accuracy& a = s.accuracy;
  t += "\n";
  if (a.has_value())
    line("gesture accuracy  %.1f %% (%lld of %lld frames; %lld settling frames skipped, %lld truth frames)\n",
         100.0 * a.value(), static_cast<long long>(a.correct), static_cast<long long>(a.evaluated),
         static_cast<long long>(a.skipped_settling), static_cast<long long>(a.truth_frames));
  else
    line("gesture accuracy  - (no frame with both GROUND_TRUTH and GESTURE_CMD after settling; %lld truth frames)\n",
         static_cast<long long>(a.truth_frames));
  const Score& r = s.reaction;
  line("gesture reaction  median %.2f s, max %.2f s over %d changes (%d missed); old command on %lld of %lld frames "
       "(%.1f %%); false at rest %d, confused %d\n",
       r.reaction_median_s(), r.reaction_max_s(), r.changes, r.missed, static_cast<long long>(r.old_frames),
       static_cast<long long>(r.frames), r.frames ? 100.0 * r.old_frames / r.frames : 0.0, r.false_at_rest, r.confused);
  line("%-18s", "expected \\ decided");
  for (int m = 0; m < kModes; ++m) line(" %8s", mode_name(m));
  t += "\n";
  for (int e = 0; e < kModes; ++e) {
    line("%-18s", mode_name(e));
    for (int d = 0; d < kModes; ++d) line(" %8lld", static_cast<long long>(a.confusion[static_cast<size_t>(e)][static_cast<size_t>(d)]));
    t += "\n";
  }
  const TrackVsTruth& tv = s.track_vs_truth;
  if (tv.frames)
    line("\ntrack vs truth    %lld frames with a true box, TRACKING %lld: on the user (IoU >= 0.5) %lld, elsewhere "
         "(IoU < 0.2) %lld; IoU mean %.3f, min %.3f\n",
         static_cast<long long>(tv.frames), static_cast<long long>(tv.tracking), static_cast<long long>(tv.on_user),
         static_cast<long long>(tv.elsewhere), tv.mean_iou(), tv.tracking ? tv.iou_min : 0.0);
  bool header = false;
  for (const auto& b : s.range_bands) {
    if (b.truth_frames == 0) continue;
    if (!header) line("%-18s %9s %9s %10s %9s %9s\n", "range (m)", "frames", "judged", "accuracy", "on user", "IoU");
    header = true;
    char name[32];
    if (std::isfinite(b.to_m)) std::snprintf(name, sizeof name, "%g-%g", b.from_m, b.to_m);
    else std::snprintf(name, sizeof name, ">= %g", b.from_m);
    char acc[16] = "-";
    if (b.evaluated) std::snprintf(acc, sizeof acc, "%.1f %%", 100.0 * b.correct / b.evaluated);
    line("%-18s %9lld %9lld %10s %9lld %9.3f\n", name, static_cast<long long>(b.truth_frames),
         static_cast<long long>(b.evaluated), acc, static_cast<long long>(b.track.on_user), b.track.mean_iou());
  }
  line("\nvehicle           %lld states, path %.2f m\n", static_cast<long long>(s.vehicle_states), s.path_length_m);
  const Engagement& e = s.engagement;
  line("engaged           %lld of %lld setpoints%s%s\n", static_cast<long long>(e.engaged_setpoints),
       static_cast<long long>(e.setpoints), e.last_refusal.empty() ? "" : "; ", e.last_refusal.c_str());
  return t;
}

}  // namespace gpilot
