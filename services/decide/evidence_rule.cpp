// EvidenceRule: per-command evidence with hysteresis (see evidence_rule.hpp).
#include "evidence_rule.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gpilot {
namespace {

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

EvidenceRule::Class EvidenceRule::classify(int kind, Vec2 v, double lambda4, double front_dead_band) {
  if (v.is_zero()) return kNone;
  if (kind == 1) {
    if (std::fabs(v.y) > std::fabs(lambda4 * v.x)) return v.y < 0.0 ? kUp : kDown;  // Alg. 3's snap, one vector
    return v.x < 0.0 ? kFineLeft : kFineRight;
  }
  if (kind == 2) {
    if (v.y < -front_dead_band) return kCloser;
    if (v.y > front_dead_band) return kFurther;
  }
  return kNone;
}

bool EvidenceRule::held_in_front(double box_width) const {
  // Talking moves the hands about in front of the body, a new place every 0.25-0.85 s: a gesture is a hand
  // that stays. Every one of the last front_hold_frames frames has a hand in front, none farther than
  // front_hold_ratio box widths from their median (one far frame is a hand on its way, or a jump: not held).
  const size_t k = static_cast<size_t>(params_.front_hold_frames);
  if (history_.size() < k) return false;
  std::vector<double> xs, ys;
  for (size_t i = history_.size() - k; i < history_.size(); ++i) {
    if (history_[i].kind != 2) return false;
    xs.push_back(history_[i].vector.x);
    ys.push_back(history_[i].vector.y);
  }
  const double mx = median(xs), my = median(ys);
  for (size_t i = 0; i < xs.size(); ++i)
    if (std::hypot(xs[i] - mx, ys[i] - my) > params_.front_hold_ratio * box_width) return false;
  return true;
}

void EvidenceRule::reset() {
  evidence_.fill(0.0);
  current_ = kNone;
  history_.clear();
  for (auto& r : recent_) r.clear();
}

Decision EvidenceRule::update(int kind, Vec2 vector, double box_width) {
  const Class c = classify(kind, vector, params_.lambda4, params_.front_dead_zone * box_width);
  // Moving: the median position of this kind of hand over the last moving_frames frames is far from its median
  // over the moving_frames before. Medians, because a hand found on a noisy image jumps by half its size now and
  // then while the arm holds still (an outlier moves no median), and a drifting arm moves both.
  history_.push_back({kind, vector});
  while (static_cast<int>(history_.size()) > std::max(2 * params_.moving_frames, params_.front_hold_frames))
    history_.pop_front();
  bool moving = false;
  if (c != kNone) {
    std::vector<double> ax, ay, bx, by;
    const int n = static_cast<int>(history_.size());
    for (int i = std::max(0, n - 2 * params_.moving_frames); i < n; ++i) {
      if (history_[static_cast<size_t>(i)].kind != kind) continue;
      const Vec2& v = history_[static_cast<size_t>(i)].vector;
      const bool recent = i >= n - params_.moving_frames;
      (recent ? ax : bx).push_back(v.x);
      (recent ? ay : by).push_back(v.y);
    }
    // Not yet 2 * moving_frames frames of this kind of hand: it just came into view, on its way.
    const size_t k = static_cast<size_t>(params_.moving_frames);
    moving = ax.size() < k || bx.size() < k ||
             std::hypot(median(ax) - median(bx), median(ay) - median(by)) > params_.moving_ratio * box_width;
  }
  // Whether this frame supports its own class. Motion matters for what is new: a frame of the held command's
  // own class supports it even while the hand moves (a held arm that jitters, or sweeps within its command, is
  // still held). Not a hand in front: a new CLOSER/FURTHER needs the hand held (held_in_front), and a held one
  // is let go when its hand moves on (talking: the next place is often on the same side of the body centre).
  bool supported = false;
  if (c == kCloser || c == kFurther) supported = !moving && (c == current_ || held_in_front(box_width));
  else if (c != kNone) supported = !moving || c == current_;

  for (int k = 1; k < kClasses; ++k) {
    const bool support = k == c && supported;
    evidence_[k] = std::clamp(evidence_[k] + (support ? 1.0 : -params_.evidence_decay), 0.0,
                              static_cast<double>(params_.evidence_max));
    if (support) {
      recent_[k].push_back(vector);
      while (static_cast<int>(recent_[k].size()) > params_.direction_frames) recent_[k].pop_front();
    }
  }
  // Leave the held command once its evidence is down to evidence_leave; enter the strongest one at or above
  // evidence_enter (the held one keeps priority while it holds).
  if (current_ != kNone && evidence_[current_] <= params_.evidence_leave) current_ = kNone;
  Class best = kNone;
  for (int k = 1; k < kClasses; ++k)
    if (evidence_[k] >= params_.evidence_enter && (best == kNone || evidence_[k] > evidence_[best])) best = static_cast<Class>(k);
  if (best != kNone && (current_ == kNone || evidence_[best] > evidence_[current_])) current_ = best;

  Decision d;
  if (current_ == kNone) return d;
  Vec2 mean;
  for (const Vec2& v : recent_[current_]) mean.x += v.x, mean.y += v.y;
  const double n = std::max<size_t>(1, recent_[current_].size());
  mean = {mean.x / n, mean.y / n};
  switch (current_) {
    case kFineLeft:
    case kFineRight: d.mode = GestureMode::Fine; d.out_mean = mean; break;
    case kUp: d.mode = GestureMode::Up; d.out_mean = {0.0, mean.y}; break;
    case kDown: d.mode = GestureMode::Down; d.out_mean = {0.0, mean.y}; break;
    case kCloser: d.mode = GestureMode::Closer; d.z = 1.0; break;
    case kFurther: d.mode = GestureMode::Further; d.z = -1.0; break;
    default: break;
  }
  return d;
}

}  // namespace gpilot
