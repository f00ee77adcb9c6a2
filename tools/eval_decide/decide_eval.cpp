#include "decide_eval.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "channels.hpp"
#include "decide/decide_service.hpp"
#include "flight/flight_bridge.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "log_reader.hpp"
#include "stage_stats.hpp"

namespace gpilot {
namespace {

constexpr int kHover = gesture_cmd_t::MODE_HOVER;
constexpr int kFine = gesture_cmd_t::MODE_FINE;

double angle_deg(const double a[2], const double b[2]) {
  const double n = std::hypot(a[0], a[1]) * std::hypot(b[0], b[1]);
  if (n <= 0) return 180.0;
  return std::acos(std::clamp((a[0] * b[0] + a[1] * b[1]) / n, -1.0, 1.0)) * 180.0 / M_PI;
}

bool right_command(const ScoredCommand& c, const TruthSegment& s, const ScoreRules& rules) {
  if (c.mode != s.mode) return false;
  return s.mode != kFine || angle_deg(c.dir, s.dir) <= rules.fine_angle_deg;
}

int64_t median_of(std::vector<int64_t> v) { return static_cast<int64_t>(quantile(v, 0.5)); }

}  // namespace

EvalLog read_eval_log(const std::string& path) {
  EvalLog out;
  out.path = path;
  LogReader log(path);
  LogDispatcher d;
  std::vector<hand_obs_t> obs;
  std::unordered_map<int64_t, ground_truth_t> truth;
  std::unordered_map<int64_t, int64_t> truth_logged;  // seq -> log time
  std::unordered_map<int64_t, ScoredCommand> cmd_of_seq;
  std::vector<std::pair<int64_t, flight_setpoint_t>> setpoints;  // log time, message
  d.on<hand_obs_t>(channel::kHandObs, [&](const hand_obs_t& m, int64_t) { obs.push_back(m); });
  d.on<ground_truth_t>(channel::kGroundTruth, [&](const ground_truth_t& m, int64_t t) {
    truth[m.seq] = m;
    truth_logged[m.seq] = t;
  });
  d.on<gesture_cmd_t>(channel::kGestureCmd, [&](const gesture_cmd_t& m, int64_t) {
    cmd_of_seq[m.seq] = {m.mode, {m.direction[0], m.direction[1]}};
  });
  d.on<flight_setpoint_t>(channel::kFlightSetpoint, [&](const flight_setpoint_t& m, int64_t t) { setpoints.push_back({t, m}); });
  LogEvent ev;
  while (log.next(ev)) d.dispatch(ev);
  if (obs.empty() || truth.empty())
    throw std::runtime_error(path + ": needs HAND_OBS and GROUND_TRUTH (has " + std::to_string(obs.size()) + " and " +
                             std::to_string(truth.size()) + ")");
  for (const auto& m : obs) {
    const auto t = truth.find(m.seq);
    if (t == truth.end()) {
      ++out.hand_obs_without_truth;
      continue;
    }
    EvalFrame f;
    f.obs = to_hand_observation(m);
    f.track.utime = m.utime;
    f.track.tracking = f.obs.tracking;
    for (int k = 0; k < 4; ++k) f.track.box[k] = m.user_box[k];
    f.track.track_id = m.track_id;
    f.track.image_width = m.image_width;
    f.track.image_height = m.image_height;
    f.gesture = t->second.gesture;
    f.expected_mode = t->second.expected_mode;
    f.expected_dir[0] = t->second.expected_direction[0];
    f.expected_dir[1] = t->second.expected_direction[1];
    out.frames.push_back(f);
  }
  if (!cmd_of_seq.empty()) {
    for (const auto& f : out.frames) {
      const auto c = cmd_of_seq.find(f.obs.seq);
      out.recorded_cmd.push_back(c == cmd_of_seq.end() ? ScoredCommand{} : c->second);
    }
  }
  if (!setpoints.empty()) {
    std::sort(setpoints.begin(), setpoints.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    size_t next = 0;
    ScoredCommand flying;
    for (size_t i = 0; i < out.frames.size(); ++i) {
      // Until the next frame's truth was logged (the last frame: one frame period on).
      const int64_t t = truth_logged[out.frames[i].obs.seq];
      const int64_t until = i + 1 < out.frames.size() ? truth_logged[out.frames[i + 1].obs.seq] : t + 40000;
      for (; next < setpoints.size() && setpoints[next].first < until; ++next) {
        const flight_setpoint_t& m = setpoints[next].second;
        const auto c = cmd_of_seq.find(m.seq);
        flying = {m.mode, {0, 0}};
        if (c != cmd_of_seq.end() && c->second.mode == m.mode) flying = c->second;
      }
      out.recorded_flown.push_back(flying);
    }
  }
  return out;
}

std::vector<TruthFrame> truth_of(const EvalLog& log) {
  std::vector<TruthFrame> t;
  t.reserve(log.frames.size());
  for (const auto& f : log.frames) t.push_back({f.obs.utime, f.gesture, f.expected_mode, {f.expected_dir[0], f.expected_dir[1]}});
  return t;
}

std::vector<TruthSegment> truth_segments(const std::vector<TruthFrame>& truth, const ScoreRules& rules) {
  std::vector<TruthSegment> segs;
  const double* ref = nullptr;  // the first FINE direction of the current OUT gesture
  for (size_t i = 0; i < truth.size(); ++i) {
    const TruthFrame& f = truth[i];
    const bool fine = f.expected_mode == kFine;
    const bool turned = f.gesture == ground_truth_t::GESTURE_OUT && fine && ref && angle_deg(ref, f.dir) > rules.turn_deg;
    if (segs.empty() || truth[segs.back().begin].gesture != f.gesture || turned) {
      if (!segs.empty()) segs.back().end = i;
      segs.push_back({i, i + 1, kHover, {0, 0}, true});
      ref = nullptr;
    }
    if (fine && !ref) ref = f.dir;
  }
  if (!segs.empty()) segs.back().end = truth.size();
  // An arm on its way out sweeps through directions; a piece cut off by a turn that does not last is part of
  // the OUT piece that follows it.
  for (size_t k = 0; k + 1 < segs.size();) {
    const bool both_out = truth[segs[k].begin].gesture == ground_truth_t::GESTURE_OUT &&
                          truth[segs[k + 1].begin].gesture == ground_truth_t::GESTURE_OUT;
    const int64_t length = truth[segs[k + 1].begin].utime - truth[segs[k].begin].utime;
    if (both_out && length < static_cast<int64_t>(rules.min_turn_s * 1e6)) {
      segs[k + 1].begin = segs[k].begin;
      segs.erase(segs.begin() + static_cast<std::ptrdiff_t>(k));
    } else {
      ++k;
    }
  }
  for (auto& s : segs) {
    if (truth[s.begin].gesture == ground_truth_t::GESTURE_REST) continue;  // HOVER, seen
    std::map<int, int> votes;
    double sx = 0, sy = 0;
    int nf = 0;
    for (size_t i = s.begin; i < s.end; ++i) {
      ++votes[truth[i].expected_mode];
      if (truth[i].expected_mode == kFine) sx += truth[i].dir[0], sy += truth[i].dir[1], ++nf;
    }
    s.mode = std::max_element(votes.begin(), votes.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
    s.seen = s.mode != kHover;
    if (nf) s.dir[0] = sx / nf, s.dir[1] = sy / nf;
  }
  return segs;
}

Score score_commands(const std::vector<TruthFrame>& truth, const std::vector<ScoredCommand>& commands,
                     const ScoreRules& rules) {
  if (commands.size() != truth.size()) throw std::invalid_argument("score_commands: one command per truth frame");
  Score s;
  const auto segs = truth_segments(truth, rules);
  int prev_false_mode = -1;  // the mode of the false command in the previous frame (-1: none)
  for (size_t k = 0; k < segs.size(); ++k) {
    const TruthSegment& seg = segs[k];
    if (!seg.seen) {
      prev_false_mode = -1;
      continue;
    }
    s.frames += static_cast<int64_t>(seg.end - seg.begin);
    const int64_t t_end = seg.end < truth.size() ? truth[seg.end].utime : truth.back().utime;
    s.minutes += (t_end - truth[seg.begin].utime) / 60e6;
    const bool change = k > 0;
    const int old_mode = change ? segs[k - 1].mode : kHover;
    bool reacted = false;
    for (size_t i = seg.begin; i < seg.end; ++i) {
      const ScoredCommand& c = commands[i];
      const bool right = right_command(c, seg, rules);
      if (right && !reacted && change) {
        s.reaction_us.push_back(truth[i].utime - truth[seg.begin].utime);
        s.reaction_frames.push_back(static_cast<int>(i - seg.begin));
      }
      const bool lag = change && !reacted && !right;
      reacted = reacted || right;
      if (!right) ++s.wrong_frames;
      if (lag) ++s.old_frames;
      // The command the paper's rules give on the true hands of this frame is not false: the next gesture's
      // while the true hand already shows it (the label switches half-way through the arm's move, the rules on
      // the true hand may switch before), or one the arm passes through on its way (an arm lowered slowly from
      // out to rest is out and down, DOWN, for a second: fine-piloting).
      const bool shown = c.mode == truth[i].expected_mode;
      const bool is_false = c.mode != kHover && c.mode != seg.mode && !(lag && c.mode == old_mode) && !shown;
      if (is_false) {
        const bool onset = prev_false_mode != c.mode;
        if (onset) s.false_list.push_back({truth[i].utime, seg.mode, c.mode, 0});
        ++s.false_list.back().frames;
        if (seg.mode == kHover) {
          ++s.false_at_rest_frames;
          if (onset) ++s.false_at_rest;
        } else {
          ++s.confused_frames;
          if (onset) ++s.confused;
        }
      }
      prev_false_mode = is_false ? c.mode : -1;
    }
    if (change) {
      ++s.changes;
      if (!reacted) ++s.missed;
      s.change_list.push_back({truth[seg.begin].utime, old_mode, seg.mode, reacted ? s.reaction_frames.back() : -1});
    }
  }
  return s;
}

void Score::add(const Score& o) {
  frames += o.frames;
  minutes += o.minutes;
  changes += o.changes;
  missed += o.missed;
  reaction_us.insert(reaction_us.end(), o.reaction_us.begin(), o.reaction_us.end());
  reaction_frames.insert(reaction_frames.end(), o.reaction_frames.begin(), o.reaction_frames.end());
  change_list.insert(change_list.end(), o.change_list.begin(), o.change_list.end());
  false_list.insert(false_list.end(), o.false_list.begin(), o.false_list.end());
  old_frames += o.old_frames;
  wrong_frames += o.wrong_frames;
  false_at_rest += o.false_at_rest;
  false_at_rest_frames += o.false_at_rest_frames;
  confused += o.confused;
  confused_frames += o.confused_frames;
}

double Score::reaction_median_s() const { return reaction_us.empty() ? NAN : median_of(reaction_us) * 1e-6; }
double Score::reaction_max_s() const {
  return reaction_us.empty() ? NAN : *std::max_element(reaction_us.begin(), reaction_us.end()) * 1e-6;
}
int Score::reaction_median_frames() const {
  std::vector<int64_t> f(reaction_frames.begin(), reaction_frames.end());
  return f.empty() ? -1 : static_cast<int>(median_of(f));
}
int Score::reaction_max_frames() const {
  return reaction_frames.empty() ? -1 : *std::max_element(reaction_frames.begin(), reaction_frames.end());
}

StageRun run_stages(const EvalLog& log, const DecideParams& decide, const FlightParams& flight) {
  StageRun r;
  GestureDecider decider(decide);
  FlightParams fp = flight;
  fp.require_vehicle_state = false;  // the log's vehicle is not part of the decision
  FlightBridge bridge(fp);
  std::unordered_map<int64_t, size_t> index_of_seq;
  for (const auto& f : log.frames) {
    const GestureCommand c = decider.update(f.obs);
    index_of_seq[c.seq] = r.decided.size();
    r.decided.push_back({static_cast<int>(c.mode), {c.direction[0], c.direction[1]}});
    // The flight stage as it runs: the latest command and track, received with the frame (the pipeline's
    // few milliseconds are left out), the operator engaged; one setpoint at each frame's time.
    BridgeInputs in;
    in.now = f.obs.utime;
    in.command = c;
    in.command_received = f.obs.utime;
    in.track = f.track;
    in.track_received = f.obs.utime;
    in.engaged = true;
    const Setpoint sp = bridge.update(in);
    ScoredCommand flown{sp.mode, {0, 0}};
    const auto it = index_of_seq.find(sp.seq);
    if (sp.mode != kHover && it != index_of_seq.end()) flown = r.decided[it->second];
    r.flown.push_back(flown);
  }
  return r;
}

}  // namespace gpilot
