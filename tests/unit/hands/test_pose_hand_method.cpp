// The pose method as gpilot-hands builds it (make_hand_method, hands.method pose) on the synthetic
// tour: each gesture held gives the scene's expected observation; a net that computes NaN is a refusal (counted by
// the service), never a pose. Needs the converted models (deploy/setup): without them these tests fail saying so.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../pose/pose_test_models.hpp"
#include "capture/synthetic_world.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "hands/hands_core_factory.hpp"
#include "hands/pose_hand_method.hpp"

namespace gpilot {
namespace {

const SyntheticWorld& tour() {
  static const SyntheticWorld world(SyntheticParams{}, Scenario::load("tour"), 3);
  return world;
}

// The method over 1 s of frames (25 fps) from 0.5 s after the gesture's key time, as the stage runs (tracking
// from frame to frame): the last output, the arm long arrived.
HandsOutput held(HandMethod& method, int gesture, SyntheticFrame* last) {
  const double t0 = *tour().scenario().key_time_of(gesture) + 0.5;
  HandsOutput out;
  method.reset();
  for (int i = 0; i < 25; ++i) {
    *last = tour().render(t0 + i * 0.04, i, std::nullopt);
    out = method.observe(last->bgr, UserView{last->truth.user_box, std::nullopt, 1}, std::llround((t0 + i * 0.04) * 1e6));
  }
  return out;
}

TEST(PoseHandMethod, EachHeldGestureOfTheTourGivesTheScenesObservation) {
  HandsParams params;
  params.method = "pose";
  if (!pose_test::models_present(params.pose)) return;
  const auto method = make_hand_method(params);
  using G = ground_truth_t;
  for (int gesture : {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN, G::GESTURE_CLOSER,
                      G::GESTURE_FURTHER}) {
    SCOPED_TRACE(gesture);
    SyntheticFrame f;
    const HandsOutput r = held(*method, gesture, &f);
    ASSERT_TRUE(r.refused.empty()) << r.refused;
    ASSERT_TRUE(r.pose.has_value());
    EXPECT_FALSE(r.skin.has_value());
    EXPECT_EQ(static_cast<int>(r.kind), f.truth.expected_kind) << r.pose->reading;
    if (r.kind == HandKind::Front) {
      // A hand in front: higher or lower than p_bc, as the scene's (decide reads only the sign).
      EXPECT_EQ(r.vector.y < 0, f.truth.expected_vector.y < 0) << r.pose->reading;
    } else if (r.kind == HandKind::Out) {
      // An arm out points where the scene's does: within 20 deg (p_uc is the landmarks', the scene's the box's).
      const double angle = std::abs(std::remainder(std::atan2(r.vector.y, r.vector.x) -
                                                       std::atan2(f.truth.expected_vector.y, f.truth.expected_vector.x),
                                                   2 * M_PI)) * 180 / M_PI;
      EXPECT_LT(angle, 20.0) << r.pose->reading;
    }
  }
}

TEST(PoseHandMethod, ANetThatGivesNaNIsARefusalNotAPose) {
  HandsParams params;
  if (!pose_test::models_present(params.pose)) return;
  PoseModels models = PoseModels::load(params.pose);
  // Every weight of both nets NaN: what a damaged model file computes.
  for (cv::dnn::Net* net : {&models.detector.net, &models.landmark.net})
    for (const std::string& name : net->getLayerNames())
      for (cv::Mat& blob : net->getLayer(name)->blobs)
        if (blob.depth() == CV_32F) blob.setTo(std::numeric_limits<float>::quiet_NaN());
  PoseHandMethod method(params, std::move(models));
  SyntheticFrame f = tour().render(*tour().scenario().key_time_of(ground_truth_t::GESTURE_OUT) + 1.5, 0, std::nullopt);
  const HandsOutput r = method.observe(f.bgr, UserView{f.truth.user_box, std::nullopt, 1}, 0);
  EXPECT_FALSE(r.refused.empty());
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_GE(method.counters().nonfinite_outputs, 1);
}

}  // namespace
}  // namespace gpilot
