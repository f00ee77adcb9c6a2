// GestureDecider: buffers each frame's Alg. 1 / Alg. 2 result and runs Alg. 3 over the last N frames.
#include "gesture_decider.hpp"

#include <cmath>

#include "clock.hpp"

namespace gpilot {

GestureDecider::GestureDecider(const DecideParams& params)
    : params_(params), s_out_(params.buffer_size), s_front_(params.buffer_size), tree_(params), evidence_(params),
      use_evidence_(params.rule == "evidence") {}

GestureCommand GestureDecider::update(const HandObservation& obs) {
  last_reset_ = Reset::None;
  if (have_last_) {
    if (obs.utime < last_utime_)
      last_reset_ = Reset::TimeBackwards;
    else if (obs.utime - last_utime_ > seconds_to_utime(params_.gap_timeout_s))
      last_reset_ = Reset::Gap;
    else if (obs.track_id != last_track_id_)
      last_reset_ = Reset::NewUser;
  }
  if (!obs.tracking) last_reset_ = Reset::NotTracking;
  if (last_reset_ != Reset::None) {
    s_out_.clear();
    s_front_.clear();
    evidence_.reset();
  }
  have_last_ = true;
  last_utime_ = obs.utime;
  last_track_id_ = obs.track_id;

  GestureCommand cmd;
  cmd.utime = obs.utime;
  cmd.seq = obs.seq;
  cmd.track_id = obs.track_id;
  cmd.user_box_width = obs.user_box_width;
  // A frame without a valid user, or whose box has no width, cannot say where a hand is: it leaves the buffers
  // empty and the command is HOVER.
  const bool usable = obs.tracking && obs.user_box_width > 0.0 && std::isfinite(obs.user_box_width) &&
                      std::isfinite(obs.vector.x) && std::isfinite(obs.vector.y);
  if (usable) {
    // Alg. 2 runs only when Alg. 1 found nothing, so one frame adds to at most one buffer.
    const Vec2 none;
    s_out_.push(obs.kind == HandObservation::Kind::Out ? obs.vector : none);
    s_front_.push(obs.kind == HandObservation::Kind::Front ? obs.vector : none);
  }
  // The buffers' counts go out with every command, whichever rule decides.
  Decision d = tree_.decide(s_out_, s_front_);
  if (use_evidence_) {
    const Decision e = usable ? evidence_.update(static_cast<int>(obs.kind), obs.vector, obs.user_box_width) : Decision{};
    d.mode = e.mode;
    d.out_mean = e.out_mean;
    d.z = e.z;
  }
  cmd.n_out = d.n_out;
  cmd.n_front_higher = d.n_front_higher;
  cmd.n_front_lower = d.n_front_lower;
  cmd.buffer_fill = s_out_.size();
  if (!usable) return cmd;
  cmd.mode = d.mode;
  cmd.direction[0] = d.out_mean.x / obs.user_box_width;
  cmd.direction[1] = d.out_mean.y / obs.user_box_width;
  cmd.direction[2] = d.z;
  return cmd;
}

}  // namespace gpilot
