// A gesture is held; gesticulation is not a command. The synthetic `talking` scenario (one hand, then both,
// then the other moving about in front of the chest and belly, no gesture held) through the default hands
// method (pose) and the default decider, open loop at 25 fps: the drone is asked to move on at most 1 frame in
// 10. With CLOSER / FURTHER entered at 3 frames of evidence and 2-frame motion medians (the defaults before
// decide.evidence_enter_front) it is asked on more, so the scenario tells the two apart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../pose/pose_test_models.hpp"
#include "capture/synthetic_world.hpp"
#include "decide/gesture_decider.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "hands/hands_core_factory.hpp"

namespace gpilot {
namespace {

TEST(Talking, HandsMovingInFrontOfTheBodyMoveTheDroneOnAtMostOneFrameInTen) {
  const HandsParams hands;
  if (!pose_test::models_present(hands.pose)) return;
  ASSERT_EQ(hands.method, "pose");
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("talking"), 1);
  const auto method = make_hand_method(hands);
  DecideParams before;
  before.evidence_enter_front = before.evidence_enter;
  before.moving_frames = 2;
  GestureDecider now{DecideParams{}}, then{before};
  const int frames = static_cast<int>(std::lround(world.scenario().duration_s() * 25));
  int moving_now = 0, moving_then = 0, judged = 0;
  for (int i = 0; i < frames; ++i) {
    const double t = i / 25.0;
    const SyntheticFrame f = world.render(t, i, std::nullopt);
    ASSERT_EQ(f.truth.gesture, ground_truth_t::GESTURE_REST) << "the scenario holds no gesture";
    const int64_t utime = 1'000'000 + i * 40'000;
    const HandsOutput r = method->observe(f.bgr, UserView{f.truth.user_box, std::nullopt, 1}, utime);
    HandObservation o;
    o.utime = utime;
    o.seq = i;
    o.track_id = 1;
    o.kind = static_cast<HandObservation::Kind>(r.kind);
    o.vector = {r.vector.x, r.vector.y};
    o.user_box_width = r.user_box.width;
    moving_now += now.update(o).mode != GestureMode::Hover;
    moving_then += then.update(o).mode != GestureMode::Hover;
    ++judged;
  }
  std::printf("talking, %d frames: a moving command on %d (%.1f %%), before %d (%.1f %%)\n", judged, moving_now,
              100.0 * moving_now / judged, moving_then, 100.0 * moving_then / judged);
  EXPECT_LE(moving_now, judged / 10);
  EXPECT_GT(moving_then, judged / 10) << "the scenario no longer tells a held gesture from talking";
}

}  // namespace
}  // namespace gpilot
