// Fuzz target: the decide core (GestureDecider, the paper's Alg. 3 over the state buffers) fed a sequence of
// HAND_OBS as check_message lets them through: times that step forward, stall, jump or go back, new users,
// lost tracks, any kind and vector. Each input is one sequence on a fresh decider. Every command it publishes
// must be a GESTURE_CMD that check_message accepts (what the flight stage takes).
#include <cstdint>

#include "decide/decide_params.hpp"
#include "decide/decide_service.hpp"
#include "decide/gesture_decider.hpp"
#include "fuzz_input.hpp"
#include "message_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  gpilot::fuzz::Input in(data, size);
  gpilot::DecideParams params;
  if (in.flag()) params.buffer_size = static_cast<int>(in.in(1, 80)), params.out_threshold = static_cast<int>(in.in(0, 80)),
                 params.front_threshold = static_cast<int>(in.in(0, 80));
  gpilot::GestureDecider decider(params);
  int64_t utime = 1'700'000'000'000'000 + in.in(0, 1'000'000);
  for (int64_t seq = 0; seq < 200 && !in.empty(); ++seq) {
    gpilot::hand_obs_t m{};
    const uint8_t step = in.byte();
    utime += step < 200 ? 33'333 : step < 240 ? in.in(-2'000'000, 2'000'000) : in.raw<int32_t>();
    m.utime = utime;
    m.seq = seq;
    const uint8_t who = in.byte();
    m.track_id = who < 240 ? 1 : static_cast<int32_t>(who % 4);
    m.track_status = who < 230 ? gpilot::user_track_t::STATUS_TRACKING : static_cast<int8_t>(who % 3);
    m.kind = static_cast<int8_t>(in.byte() % 3);
    m.image_width = 640;
    m.image_height = 480;
    const float box[4] = {200, 40, 120 + in.coordinate() / 16.0f, 360};
    for (int i = 0; i < 4; ++i) m.user_box[i] = box[i];
    if (in.byte() >= 250) m.user_box[2] = in.f32();
    m.vector[0] = in.coordinate() / 4.0f - 256.0f;
    m.vector[1] = in.coordinate() / 4.0f - 256.0f;
    if (!gpilot::check_message(m).empty()) continue;  // rejected by BusNode before the stage
    const gpilot::GestureCommand c = decider.update(gpilot::to_hand_observation(m));
    const std::string why = gpilot::check_message(gpilot::to_message(c));
    if (!why.empty()) gpilot::fuzz::fail("decide published a GESTURE_CMD that is rejected: " + why);
  }
  return 0;
}
