// The decide stage on a bus: HAND_OBS in, GESTURE_CMD out (one per HAND_OBS, with that frame's seq and
// utime). Used by gpilot-decide (live LCM) and gpilot-replay (a log through memq://).
#include <cstdio>

#include "bus_node.hpp"
#include "decide_channels.hpp"
#include "gesture_decider.hpp"
#include "decide_service.hpp"

namespace gpilot {

static_assert(static_cast<int>(GestureMode::Hover) == gesture_cmd_t::MODE_HOVER &&
                  static_cast<int>(GestureMode::Fine) == gesture_cmd_t::MODE_FINE &&
                  static_cast<int>(GestureMode::Up) == gesture_cmd_t::MODE_UP &&
                  static_cast<int>(GestureMode::Down) == gesture_cmd_t::MODE_DOWN &&
                  static_cast<int>(GestureMode::Closer) == gesture_cmd_t::MODE_CLOSER &&
                  static_cast<int>(GestureMode::Further) == gesture_cmd_t::MODE_FURTHER,
              "GestureMode and gesture_cmd_t::MODE_* must agree");

HandObservation to_hand_observation(const hand_obs_t& m) {
  HandObservation o;
  o.utime = m.utime;
  o.seq = m.seq;
  o.track_id = m.track_id;
  o.tracking = m.track_status == user_track_t::STATUS_TRACKING;
  o.kind = static_cast<HandObservation::Kind>(m.kind);
  o.vector = {m.vector[0], m.vector[1]};
  o.user_box_width = m.user_box[2];
  return o;
}

namespace {

const char* reset_reason(GestureDecider::Reset r) {
  switch (r) {
    case GestureDecider::Reset::Gap: return "gap in HAND_OBS: buffers emptied";
    case GestureDecider::Reset::NewUser: return "new user track: buffers emptied";
    case GestureDecider::Reset::TimeBackwards: return "HAND_OBS time went backwards: buffers emptied";
    default: return nullptr;
  }
}

}  // namespace

gesture_cmd_t to_message(const GestureCommand& c) {
  gesture_cmd_t m{};
  m.utime = c.utime;
  m.seq = c.seq;
  m.track_id = c.track_id;
  m.mode = static_cast<int8_t>(c.mode);
  for (int i = 0; i < 3; ++i) m.direction[i] = static_cast<float>(c.direction[i]);
  m.user_box_width = static_cast<float>(c.user_box_width);
  m.n_out = static_cast<int16_t>(c.n_out);
  m.n_front_higher = static_cast<int16_t>(c.n_front_higher);
  m.n_front_lower = static_cast<int16_t>(c.n_front_lower);
  m.buffer_fill = static_cast<int16_t>(c.buffer_fill);
  return m;
}

std::shared_ptr<void> start_decide_service(const Config& config, BusNode& node) {
  auto decider = std::make_shared<GestureDecider>(config.section<DecideParams>("decide"));
  subscribe(node, decide_channels::kHandObs, [&node, d = decider.get()](const hand_obs_t& m, int64_t) {
    const gesture_cmd_t out = to_message(d->update(to_hand_observation(m)));
    if (const char* why = reset_reason(d->last_reset())) node.set_state(health_t::STATE_OK, why);
    publish(node, decide_channels::kGestureCmd, out);
  });
  node.set_state(health_t::STATE_OK, "waiting for HAND_OBS");
  return decider;
}

}  // namespace gpilot

