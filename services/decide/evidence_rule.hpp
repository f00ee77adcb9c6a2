// EvidenceRule (decide.rule: evidence): a faster alternative to Alg. 3's 60-frame majority, with hysteresis.
// Each frame's observation is classified on its own (OUT by the lambda4 snap: UP, DOWN, FINE to the image's
// left or right; FRONT: CLOSER above the body centre, FURTHER below). Every command has an evidence count:
// +1 for a frame of its class while the hand holds still, -decay otherwise, between 0 and evidence_max. A
// command is entered once its evidence reaches evidence_enter (the strongest one wins) and left when it falls to
// evidence_leave (a CUSUM / sequential test in frames: a steady pose needs evidence_enter frames, a stray frame
// decays away, and the pose just held needs (evidence_max - evidence_leave) / decay frames to be let go).
// A hand whose median position over the last moving_frames frames is more than moving_ratio box widths from its
// median over the moving_frames before is on its way somewhere: it is evidence for nothing (an arm going out or
// coming down passes through the DOWN sector for ~0.3 s; lowered slowly, for over a second: only the drift over
// several frames tells it from a held pose, and the medians ignore the jumps of a hand found on a noisy image).
// A hand in front is held, not waved about: CLOSER/FURTHER gain evidence only once the hand has been in front
// for front_hold_frames frames, all within front_hold_ratio box widths of their median (a person talking moves
// their hands to a new place every 0.25-0.85 s: gesticulation is not a command), and a held CLOSER/FURTHER
// loses it while its hand moves. A hand in front within front_dead_zone box widths of the body centre's height
// is neither (a hand on its way up or down, or read there by the hands stage, asks for nothing).
// FINE's direction is the mean of the last direction_frames vectors of its class, UP/DOWN's the mean y.
#pragma once

#include <array>
#include <deque>

#include "decide_params.hpp"
#include "decision_tree.hpp"

namespace gpilot {

class EvidenceRule {
 public:
  // The commands the rule tells apart: FINE is two, so that pointing the other way is a new command and not
  // an average of both arms.
  enum Class { kNone = 0, kFineLeft, kFineRight, kUp, kDown, kCloser, kFurther, kClasses };

  explicit EvidenceRule(const DecideParams& params) : params_(params) {}

  // kind: 0 none, 1 OUT, 2 FRONT (hand_obs_t::KIND_*); vector in px; box_width > 0.
  Decision update(int kind, Vec2 vector, double box_width);
  void reset();

  // This frame's class from one observation (exposed for tests); a hand in front within front_dead_band px of
  // the body centre's height is neither higher nor lower.
  static Class classify(int kind, Vec2 v, double lambda4, double front_dead_band = 0.0);
  double evidence(Class c) const { return evidence_[c]; }
  Class current() const { return current_; }

 private:
  bool held_in_front(double box_width) const;

  DecideParams params_;
  std::array<double, kClasses> evidence_{};
  Class current_ = kNone;
  struct Seen { int kind; Vec2 vector; };
  std::deque<Seen> history_;  // the last max(2 * moving_frames, front_hold_frames) observations
  std::array<std::deque<Vec2>, kClasses> recent_;  // the last direction_frames supporting vectors per class
};

}  // namespace gpilot
