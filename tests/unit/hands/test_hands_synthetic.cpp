// The hands stage on frames of the synthetic world (scenario `tour`, the true user box): at every key pose of
// the script, resting hands give NONE, a stretched-out arm gives OUT with a vector within 5 degrees and 10 %
// of the true one, a hand in front of the body above its centre gives FRONT with y < 0. And resting hands
// close up, where the body overflows the image.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "capture/synthetic_world.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "hands/hand_detector.hpp"
#include "hands/skin_hand_method.hpp"
#include "paths.hpp"

using namespace gpilot;

namespace {

struct KeyPose {
  double t;
  SyntheticFrame frame;
  HandResult result;
};

std::vector<KeyPose> run_tour() {
  const HandsParams p;
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("tour"), 1);
  HandDetector d(p, SkinClassifier(SkinModel::load(resolve_project_path(p.skin.model)), p.skin.threshold));
  std::vector<KeyPose> out;
  for (const double t : world.scenario().key_times()) {
    KeyPose k{t, world.render(t, static_cast<int64_t>(std::lround(t * world.params().fps)), std::nullopt), {}};
    k.result = d.detect(k.frame.bgr, k.frame.truth.user_box);
    out.push_back(std::move(k));
  }
  return out;
}

double angle_deg(cv::Point2f a, cv::Point2f b) {
  return std::abs(std::remainder(std::atan2(a.y, a.x) - std::atan2(b.y, b.x), 2 * M_PI)) * 180 / M_PI;
}

}  // namespace

TEST(HandsSynthetic, EveryKeyPoseOfTheTour) {
  const auto poses = run_tour();
  ASSERT_GE(poses.size(), 10u);
  int rest = 0, out = 0, closer = 0;
  for (const auto& k : poses) {
    const auto& truth = k.frame.truth;
    const auto& r = k.result;
    SCOPED_TRACE("t = " + std::to_string(k.t) + " s, gesture " + std::to_string(truth.gesture));
    switch (truth.gesture) {
      case ground_truth_t::GESTURE_REST:
        ++rest;
        EXPECT_EQ(r.kind, HandKind::None) << "vector " << r.vector;
        break;
      case ground_truth_t::GESTURE_OUT:
      case ground_truth_t::GESTURE_UP:
      case ground_truth_t::GESTURE_DOWN: {
        ++out;
        ASSERT_EQ(truth.expected_kind, static_cast<int>(HandKind::Out));
        ASSERT_EQ(r.kind, HandKind::Out);
        const cv::Point2f tv = truth.expected_vector;
        EXPECT_LT(angle_deg(r.vector, tv), 5.0) << r.vector << " vs " << tv;
        EXPECT_NEAR(std::hypot(r.vector.x, r.vector.y), std::hypot(tv.x, tv.y), 0.1 * std::hypot(tv.x, tv.y));
        // Mirror: the user's right arm shows on the image's left, x < 0, and the sign is kept.
        if (std::abs(tv.x) > 10) {
          EXPECT_EQ(r.vector.x < 0, tv.x < 0);
        }
        break;
      }
      case ground_truth_t::GESTURE_CLOSER:
        ++closer;
        ASSERT_EQ(r.kind, HandKind::Front);
        EXPECT_LT(r.vector.y, 0) << "higher than the body centre";
        break;
      default:
        break;
    }
  }
  EXPECT_GE(rest, 3);
  EXPECT_GE(out, 4);
  EXPECT_GE(closer, 1);
}

// The user at rest, the drone closing in from 3 m to 1.1 m at 1.5 m and 2 m up: with the true box, no hand at
// any range (the body overflows the image from about 2 m). The same frames with a box a quarter too small,
// as a tracker whose scale lags the approach gives, do show one: the resting hand falls outside the box (OUT),
// or the neck falls below the box's face band (FRONT, above the centre: CLOSER, nearer still). That is why
// the tracker re-anchors its scale on the face and flight stops closing in at closest_box_height_ratio.
TEST(HandsSynthetic, RestingHandsAreNoHandAtAnyRangeWithTheRightBox) {
  const HandsParams p;
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("idle"), 1);
  HandDetector d(p, SkinClassifier(SkinModel::load(resolve_project_path(p.skin.model)), p.skin.threshold));
  int with_small_box = 0, frames = 0;
  for (const double alt : {1.5, 2.0})
    for (int cm = 300; cm >= 110; cm -= 10) {
      const CameraPose pose{3.0 - cm / 100.0, 0.0, -alt, 0.0};
      const SyntheticFrame f = world.render(1.0, 25, pose);
      ++frames;
      const HandResult r = d.detect(f.bgr, f.truth.user_box);
      EXPECT_EQ(r.kind, HandKind::None) << alt << " m up, " << cm << " cm away: vector " << r.vector;
      cv::Rect2f small = f.truth.user_box;
      small.x += small.width / 8;
      small.width *= 0.75f;
      small.height *= 0.75f;
      if (d.detect(f.bgr, small).kind != HandKind::None) ++with_small_box;
    }
  std::printf("a box a quarter too small gives a hand on %d of %d resting frames\n", with_small_box, frames);
  EXPECT_GT(with_small_box, frames / 2);
}

// The same approach, the box 0.15 face heights higher than the true one (a re-anchor with the track's fitted
// ratios put a closed-loop `closer-further` box 8 px above the truth at 1.9 m: the chin sat at the face band's
// end, the whole neck in the front band, and the resting user's neck was a hand in front, CLOSER for 1 s). With
// the user's face known (hands.neck_in_faces) the neck below it is removed: no hand at any range.
TEST(HandsSynthetic, TheNeckBelowAKnownFaceIsNoHandInFrontWhenTheBoxSitsHigh) {
  const HandsParams p;
  HandsParams box_ratio_only = p;
  box_ratio_only.neck_in_faces = 0;
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("idle"), 1);
  const SkinClassifier skin(SkinModel::load(resolve_project_path(p.skin.model)), p.skin.threshold);
  HandDetector with_face(p, skin), without(box_ratio_only, skin);
  int neck_as_hand = 0, frames = 0;
  for (const double alt : {1.5, 2.0})
    for (int cm = 300; cm >= 110; cm -= 10) {
      const SyntheticFrame f = world.render(1.0, 25, CameraPose{3.0 - cm / 100.0, 0.0, -alt, 0.0});
      cv::Rect2f high = f.truth.user_box;
      high.y -= 0.15f * f.truth.face_box.height;
      ++frames;
      const HandResult r = with_face.detect(f.bgr, high, nullptr, cv::Rect2f(f.truth.face_box));
      EXPECT_EQ(r.kind, HandKind::None) << alt << " m up, " << cm << " cm away: vector " << r.vector;
      const HandResult n = without.detect(f.bgr, high);
      if (n.kind == HandKind::Front && n.vector.y < 0) ++neck_as_hand;
    }
  std::printf("the box's ratio alone: the neck a hand in front on %d of %d resting frames\n", neck_as_hand, frames);
  EXPECT_GT(neck_as_hand, 0);
}

// The tracker gives the face about once a second: the stage carries the last one along with the box between, and
// forgets it with the track.
TEST(HandsSynthetic, TheLastFaceIsCarriedWithTheBoxUntilTheTrackChanges) {
  const HandsParams p;
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("idle"), 1);
  const SyntheticFrame f = world.render(1.0, 25, CameraPose{3.0 - 1.9, 0.0, -1.5, 0.0});
  cv::Rect2f high = f.truth.user_box;
  high.y -= 0.15f * f.truth.face_box.height;
  SkinHandMethod obs(p, SkinModel::load(resolve_project_path(p.skin.model)));
  // With the face given the neck below it is cleared (hands.neck_in_faces), whatever the box: the high box is on
  // the frames without it.
  EXPECT_EQ(obs.detect(f.bgr, UserView{high, cv::Rect2f(f.truth.face_box), 1}).kind, HandKind::None);
  for (int i = 0; i < 3; ++i) {
    const HandResult r = obs.detect(f.bgr, UserView{high, std::nullopt, 1});
    EXPECT_EQ(r.kind, HandKind::None) << "frame " << i + 1 << " after the face: vector " << r.vector;
  }
  // A new track: the face is not this track's; the box's ratio alone shows the neck.
  const HandResult fresh = obs.detect(f.bgr, UserView{high, std::nullopt, 2});
  EXPECT_EQ(fresh.kind, HandKind::Front) << fresh.vector;
  EXPECT_LT(fresh.vector.y, 0);
}

// A skin-coloured patch of scenery at the bottom beside a resting user, joined to their hanging forearm (the
// closed-loop `nuisances` runs: a yellow palace wall at the frame's bottom edge read as an OUT hand while the
// drone was high, a false DOWN at rest). With a forearm hanging at rest on that side, that arm is down: no hand
// of it is stretched out (hands.out_not_beside_hanging_forearm).
TEST(HandsSynthetic, NoStretchedOutHandOnTheSideOfAForearmHangingAtRest) {
  HandsParams p;
  p.skin.adapt.enabled = false;
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("idle"), 1);
  const SkinClassifier skin(SkinModel::load(resolve_project_path(p.skin.model)), p.skin.threshold);
  const SyntheticFrame f = world.render(1.0, 25, std::nullopt);
  const cv::Rect2f box = f.truth.user_box;
  // The forearm hanging on the image's right: its lowest skin pixel, and its colour.
  const cv::Point2f wrist = f.truth.left_wrist;
  ASSERT_GT(wrist.x, box.x + box.width / 2) << "the user's left hand is on the image's right";
  const cv::Vec3b tone = f.bgr.at<cv::Vec3b>(cv::Point(wrist));
  // A patch of that colour 3 px beside the forearm's outer edge (apart from it, as the opened wall was; the arm
  // test's closing joins them), out to 0.6 box widths beside the box (less than max_blob_hand_areas).
  int edge = static_cast<int>(wrist.x);
  while (edge < f.bgr.cols - 1 && cv::norm(f.bgr.at<cv::Vec3b>(cv::Point(edge + 1, static_cast<int>(wrist.y))), tone, cv::NORM_L1) < 60) ++edge;
  cv::Mat scene = f.bgr.clone();
  const float s = box.width / 4;
  const float x0 = static_cast<float>(edge + 4);
  cv::rectangle(scene, cv::Rect2f(x0, wrist.y - s, box.x + box.width + 0.6f * box.width - x0, 1.5f * s),
                cv::Scalar(tone[0], tone[1], tone[2]), cv::FILLED);
  HandDetector with_rule(p, skin);
  HandsParams off = p;
  off.out_not_beside_hanging_forearm = false;
  HandDetector without(off, skin);
  const HandResult w = without.detect(scene, box);
  EXPECT_EQ(w.kind, HandKind::Out) << "the patch should be an OUT hand without the rule: blobs " << w.blobs_dropped
                                    << ", armless " << w.armless_dropped << ", outside " << w.skin_outside << ", box " << box;
  const HandResult r = with_rule.detect(scene, box);
  EXPECT_EQ(r.kind, HandKind::None) << r.vector;
  // The untouched frame: no hand either way.
  EXPECT_EQ(with_rule.detect(f.bgr, box).kind, HandKind::None);
}
