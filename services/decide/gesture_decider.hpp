// GestureDecider: the decide stage's core. One hand observation in, one gesture command out; keeps S_out and
// S_front and empties them when the history would be stale (a gap, a new user, a lost track).
#pragma once

#include <cstdint>

#include "decision_tree.hpp"
#include "evidence_rule.hpp"

namespace gpilot {

// One frame of HAND_OBS, as the core needs it.
struct HandObservation {
  enum class Kind : int8_t { None = 0, Out = 1, Front = 2 };  // values equal hand_obs_t::KIND_*
  int64_t utime = 0;
  int64_t seq = 0;
  int32_t track_id = 0;
  bool tracking = true;  //!< the track was TRACKING in this frame (not SEARCHING or LOST)
  Kind kind = Kind::None;
  Vec2 vector;                  //!< px, from p_uc (Out) or p_bc (Front)
  double user_box_width = 0.0;  //!< px
};

class GestureDecider {
 public:
  explicit GestureDecider(const DecideParams& params);

  // Why the buffers were emptied before this observation (for HEALTH and tests); None most of the time.
  enum class Reset { None, Gap, NewUser, NotTracking, TimeBackwards };

  GestureCommand update(const HandObservation& obs);
  Reset last_reset() const { return last_reset_; }

 private:
  DecideParams params_;
  StateBuffer s_out_;
  StateBuffer s_front_;
  DecisionTree tree_;
  EvidenceRule evidence_;
  bool use_evidence_;
  bool have_last_ = false;
  int64_t last_utime_ = 0;
  int32_t last_track_id_ = 0;
  Reset last_reset_ = Reset::None;
};

}  // namespace gpilot
