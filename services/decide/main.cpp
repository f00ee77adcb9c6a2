// gpilot-decide: reads HAND_OBS, runs the state buffers and Alg. 3, writes GESTURE_CMD (one per HAND_OBS,
// with that frame's seq and utime). Also HEALTH.
#include <cstdio>

#include "bus_node.hpp"
#include "gesture_decider.hpp"
#include "service_cli.hpp"

namespace gpilot {
namespace {

static_assert(static_cast<int>(GestureMode::Hover) == gesture_cmd_t::MODE_HOVER &&
                  static_cast<int>(GestureMode::Fine) == gesture_cmd_t::MODE_FINE &&
                  static_cast<int>(GestureMode::Up) == gesture_cmd_t::MODE_UP &&
                  static_cast<int>(GestureMode::Down) == gesture_cmd_t::MODE_DOWN &&
                  static_cast<int>(GestureMode::Closer) == gesture_cmd_t::MODE_CLOSER &&
                  static_cast<int>(GestureMode::Further) == gesture_cmd_t::MODE_FURTHER,
              "GestureMode and gesture_cmd_t::MODE_* must agree");

HandObservation to_core(const hand_obs_t& m) {
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

const char* reset_reason(GestureDecider::Reset r) {
  switch (r) {
    case GestureDecider::Reset::Gap: return "gap in HAND_OBS: buffers emptied";
    case GestureDecider::Reset::NewUser: return "new user track: buffers emptied";
    case GestureDecider::Reset::TimeBackwards: return "HAND_OBS time went backwards: buffers emptied";
    default: return nullptr;
  }
}

}  // namespace
}  // namespace gpilot

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-decide",
                 "gpilot-decide: the paper's Alg. 3. Keeps the last N hand observations in S_out and S_front and\n"
                 "publishes one GESTURE_CMD per HAND_OBS (mode, camera-frame direction, buffer counts).\n"
                 "Reads HAND_OBS; writes GESTURE_CMD, HEALTH. Config section: decide.");
  return cli.run_node(argc, argv, [](const Config& config, BusNode& node) {
    GestureDecider decider(config.section<DecideParams>("decide"));
    node.subscribe<hand_obs_t>("HAND_OBS", [&](const hand_obs_t& m, int64_t) {
      const gesture_cmd_t out = to_message(decider.update(to_core(m)));
      if (const char* why = reset_reason(decider.last_reset())) node.set_state(health_t::STATE_OK, why);
      node.publish("GESTURE_CMD", out);
    });
    node.set_state(health_t::STATE_OK, "waiting for HAND_OBS");
    node.run();
    return 0;
  });
}
