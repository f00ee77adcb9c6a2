// The hands stage (make_hand_method, as gpilot-hands runs it) on the synthetic scenes that defeat a skin table
// alone: `nuisances` with its background photo as shot, `warm-wall` (a light pine wall 1 m behind a user in
// short sleeves: 94.7 % of its pixels are skin to the table) and `dark-skin`. True user box; the true face
// handed over on the first frame and every tracker.face_recheck_frames, as the tracker does. Every 5th frame.
// Measured (services/hands/README.md): the paper's stage 45-57 %, ours 96-98 %. And `orange-shirt`: the tour by
// a user in the T-shirt colour of the man in data/tracking/cf_tracking_sample, which the table calls skin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "capture/synthetic_world.hpp"
#include "config.hpp"
#include "hands/hands_core_factory.hpp"
#include "tracker/tracker_params.hpp"

using namespace gpilot;

namespace {

double kind_accuracy(const std::string& scenario, const HandsParams& hands) {
  const Config config;
  const SyntheticWorld world(config.section<SyntheticParams>("synthetic"), Scenario::load(scenario), 1);
  const auto method = make_hand_method(hands);
  const double fps = world.params().fps;
  const int frames = static_cast<int>(world.scenario().duration_s() * fps);
  const int stride = 5, recheck = config.section<TrackerParams>("tracker").face_recheck_frames;
  int right = 0, scored = 0;
  for (int i = 0; i < frames; i += stride) {
    const SyntheticFrame f = world.render(i / fps, i, std::nullopt);
    const bool face = i == 0 || i % recheck < stride;
    const HandsOutput r =
        method->observe(f.bgr, UserView{f.truth.user_box, face ? std::optional(f.truth.face_box) : std::nullopt, 1}, std::llround(1e6 * i / fps));
    right += static_cast<int>(r.kind) == std::clamp(f.truth.expected_kind, 0, 2);
    ++scored;
  }
  return static_cast<double>(right) / scored;
}

// The skin method as configured by default (these scenes are a skin table's trials).
HandsParams skin_stage() {
  HandsParams p;
  p.method = "skin";
  return p;
}

HandsParams papers_stage() {
  HandsParams p = skin_stage();
  p.skin.adapt.enabled = false;
  p.max_blob_hand_areas = 0;
  p.reach_ratio = 0;
  p.out_min_angle_deg = 0;
  p.arm_connected = false;
  p.front_max_upright = 0;
  p.front_max_hand_areas = 0;
  return p;
}

}  // namespace

class HandsScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(HandsScenes, TheAdaptedStageGetsNineInTenWhereTheTableAloneFails) {
  EXPECT_GE(kind_accuracy(GetParam(), skin_stage()), 0.90);
  EXPECT_LE(kind_accuracy(GetParam(), papers_stage()), 0.65);  // the scene does defeat the table alone
}

INSTANTIATE_TEST_SUITE_P(AsShot, HandsScenes, ::testing::Values("nuisances", "warm-wall", "dark-skin"),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

TEST(HandsScenesOrangeShirt, TheShirtIsNoHandAndTheHandsInFrontOfItAreFound) {
  // The paper's stage takes the shirt for a hand in front whenever the user rests (73.6 % overall, every REST
  // frame FRONT); without the clothing model the torso-size rule drops the hands in front too (78.1 %).
  EXPECT_GE(kind_accuracy("orange-shirt", skin_stage()), 0.90);
  EXPECT_LE(kind_accuracy("orange-shirt", papers_stage()), 0.80);
  HandsParams no_clothing = skin_stage();
  no_clothing.skin.adapt.clothing_weight = 0;
  EXPECT_LE(kind_accuracy("orange-shirt", no_clothing), 0.85);
}

TEST(HandsScenesTruth, AMisSetStageScoresLowerAgainstTheScenesTruth) {
  // The truth is the scene's (gesture_truth.hpp, truth_rules), not the stage's config: a search rectangle
  // narrowed to 0.1 box widths each side (default 1.2) misses the stretched-out hands, and the score says so.
  HandsParams narrow = skin_stage();
  narrow.roi_extend_side = 0.1;
  const double right = kind_accuracy("tour", skin_stage()), mis_set = kind_accuracy("tour", narrow);
  EXPECT_GE(right, 0.95);
  EXPECT_LT(mis_set, right - 0.10) << mis_set << " vs " << right;
}
