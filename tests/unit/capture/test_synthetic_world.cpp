// The synthetic world: ground truth agrees with the picture (at three distances and two yaws), the closed loop
// moves the person in the image the right way, the expected commands of the tour are its gestures, renders
// are deterministic, and the person's colours work with the project's real skin model.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "hands/hands_params.hpp"
#include "hands/skin_model.hpp"
#include "paths.hpp"
#include "synthetic_world.hpp"

namespace gpilot {
namespace {

const SyntheticWorld& tour_world() {
  static const SyntheticWorld world(SyntheticParams{}, Scenario::load("tour"), 7);
  return world;
}

// Scenario time at which the tour holds a gesture (the first keyframe with it).
double tour_time_of(int gesture) {
  if (const auto t = tour_world().scenario().key_time_of(gesture)) return *t;
  ADD_FAILURE() << "tour has no " << gesture_name(gesture);
  return 0.0;
}

cv::Rect2f grown(const cv::Rect2f& r, float px) { return {r.x - px, r.y - px, r.width + 2 * px, r.height + 2 * px}; }

cv::Rect2f hand_box(const cv::Point2f& c, float size) { return {c.x - size / 2, c.y - size / 2, size, size}; }

// Pixels of a label, and how many of them lie outside a rectangle.
struct LabelCount {
  int total = 0, outside = 0;
};
LabelCount count_label(const cv::Mat& labels, PartLabel label, const cv::Rect2f& inside) {
  LabelCount c;
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      if (labels.at<uchar>(y, x) != static_cast<uchar>(label)) continue;
      ++c.total;
      if (!inside.contains(cv::Point2f(x + 0.5f, y + 0.5f))) ++c.outside;
    }
  return c;
}

struct ViewCase {
  double distance_m, yaw_rad;
};

class TruthAgreesWithPicture : public ::testing::TestWithParam<ViewCase> {};

TEST_P(TruthAgreesWithPicture, HandsInTheirBoxesFaceAtTheTopOfTheUserBox) {
  const ViewCase vc = GetParam();
  const SyntheticWorld& w = tour_world();
  // GIVEN the drone at the given distance in front of the person (who stands 3 m north), yawed
  const CameraPose cam{3.0 - vc.distance_m, 0.0, -1.5, vc.yaw_rad};
  for (int gesture : {ground_truth_t::GESTURE_REST, ground_truth_t::GESTURE_OUT, ground_truth_t::GESTURE_CLOSER,
                      ground_truth_t::GESTURE_DOWN}) {
    SCOPED_TRACE(gesture_name(gesture));
    cv::Mat labels;
    const SyntheticFrame f = w.render(tour_time_of(gesture), 0, cam, &labels);
    const SyntheticTruth& t = f.truth;
    // THEN every pixel of each hand (in the picture) lies in its ground-truth hand square
    const cv::Rect2f image(0, 0, 640, 480);
    for (auto [label, centre] : {std::pair{PartLabel::RightHand, t.right_hand}, std::pair{PartLabel::LeftHand, t.left_hand}}) {
      const cv::Rect2f box = hand_box(centre, t.hand_size);
      if ((box & image) != box) continue;  // stretched out of the picture at 2 m
      const LabelCount c = count_label(labels, label, grown(box, 1.0f));
      EXPECT_GT(c.total, 20) << "hand hardly visible";
      EXPECT_EQ(c.outside, 0) << c.outside << " of " << c.total << " hand pixels outside the hand box";
    }
    // the face box sits inside the top of the user box, and the whole head inside the user box
    const cv::Rect2f& u = t.user_box;
    EXPECT_TRUE((t.face_box & u) == t.face_box);
    EXPECT_LT(t.face_box.y - u.y, 0.1f * u.height);
    // (only the hair may rise above the box: its top is 0.25 face heights above the face box, the hair 0.53)
    const cv::Rect2f with_hair(u.x, u.y - 0.35f * t.face_box.height, u.width, u.height);
    EXPECT_EQ(count_label(labels, PartLabel::Head, grown(with_hair, 1.0f)).outside, 0);
    // the torso is inside the user box apart from the hips below it
    const LabelCount torso = count_label(labels, PartLabel::Torso, grown(u, 1.0f));
    EXPECT_LT(torso.outside, torso.total / 20);
    // the user box sits where the person is: its centre x within a face width of the face's centre
    EXPECT_NEAR(u.x + u.width / 2, t.face_box.x + t.face_box.width / 2, 1e-3);
    if (gesture == ground_truth_t::GESTURE_REST) {
      // resting hands lie inside the user box, more than half a hand (0.092 box widths) from its sides
      for (const auto& h : {t.right_hand, t.left_hand}) {
        EXPECT_TRUE(u.contains(h));
        EXPECT_GT(std::min(h.x - u.x, u.x + u.width - h.x), 0.1f * u.width);
      }
    }
    if (gesture == ground_truth_t::GESTURE_OUT) {
      // a stretched-out hand is far outside it (the user's right hand: the image's left)
      EXPECT_LT(t.right_hand.x, u.x - 0.5f * u.width);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ThreeDistancesTwoYaws, TruthAgreesWithPicture,
                         ::testing::Values(ViewCase{2.0, 0.0}, ViewCase{3.0, 0.0}, ViewCase{5.0, 0.0},
                                           ViewCase{2.0, 0.2}, ViewCase{3.0, -0.2}, ViewCase{5.0, 0.2}));

TEST(SyntheticWorld, DefaultCameraSeesThePersonFromThreeMetres) {
  const SyntheticFrame f = tour_world().render(1.0, 0, std::nullopt);
  EXPECT_EQ(f.bgr.cols, 640);
  EXPECT_EQ(f.bgr.rows, 480);
  EXPECT_EQ(f.bgr.type(), CV_8UC3);
  // 0.17 m face at 3 m with f = 320 / tan(30 deg) = 554.3 px, and the cascade's box on it 1.1x that
  EXPECT_NEAR(f.truth.face_box.width, 554.256 * 0.17 * 1.1 / 3.0, 0.5);
  EXPECT_NEAR(f.truth.face_box.x + f.truth.face_box.width / 2, 320.0, 0.5);
  // p_uc and p_bc are the figure's: its shoulder joints 1.44 m up, midway to its hips 1.16 m up, seen level from
  // 1.5 m (the box's 0.2 and 0.5 of its height would give y 239.2 and 305.1)
  EXPECT_NEAR(f.truth.shoulder_centre.x, 320.0, 0.5);
  EXPECT_NEAR(f.truth.shoulder_centre.y, 240.0 + 554.256 * (1.5 - 1.44) / 3.0, 0.5);
  EXPECT_NEAR(f.truth.body_centre.x, 320.0, 0.5);
  EXPECT_NEAR(f.truth.body_centre.y, 240.0 + 554.256 * (1.5 - 1.16) / 3.0, 0.5);
  EXPECT_FLOAT_EQ(f.truth.person_position.x, 3.0f);
  EXPECT_FLOAT_EQ(f.truth.person_position.z, 0.0f);
  EXPECT_DOUBLE_EQ(f.truth.camera.down, -1.5);
}

TEST(SyntheticWorld, ClosedLoopCloserIsLargerAndYawMovesThePersonAcross) {
  const SyntheticWorld& w = tour_world();
  const SyntheticTruth far = w.render(1.0, 0, CameraPose{0.0, 0.0, -1.5, 0.0}).truth;
  const SyntheticTruth near = w.render(1.0, 0, CameraPose{1.5, 0.0, -1.5, 0.0}).truth;
  // 3 m -> 1.5 m: twice as large
  EXPECT_NEAR(near.face_box.width / far.face_box.width, 2.0, 0.02);
  // yawing right (clockwise, positive) moves the person to the image's left, by f * tan(yaw)
  const SyntheticTruth yawed = w.render(1.0, 0, CameraPose{0.0, 0.0, -1.5, 0.1}).truth;
  const float cx_far = far.face_box.x + far.face_box.width / 2, cx_yawed = yawed.face_box.x + yawed.face_box.width / 2;
  EXPECT_NEAR(cx_far - cx_yawed, 554.256 * std::tan(0.1), 2.0);
  // climbing moves the person down in the image
  const SyntheticTruth higher = w.render(1.0, 0, CameraPose{0.0, 0.0, -2.5, 0.0}).truth;
  EXPECT_GT(higher.face_box.y, far.face_box.y + 50);
}

TEST(SyntheticWorld, ThePersonTurnsToFaceTheDroneUnlessTheirFacingIsFixed) {
  // GIVEN the drone 3 m from the person but 60 deg round to their side, looking at them
  const double a = 60.0 * M_PI / 180.0;
  const CameraPose side{3.0 - 3.0 * std::cos(a), -3.0 * std::sin(a), -1.5, a};
  const SyntheticTruth turning = tour_world().render(1.0, 0, side).truth;
  const SyntheticWorld fixed(SyntheticParams{}, Scenario::parse("person: {facing_yaw_deg: 180}\nkeyframes: [{t: 0}]\n", "x"), 1);
  const SyntheticTruth still = fixed.render(1.0, 0, side).truth;
  // THEN a person who turns shows the full face width; one who does not is seen foreshortened (cos 60 deg)
  EXPECT_NEAR(turning.face_box.width, 554.256 * 0.17 * 1.1 / 3.0, 1.0);
  EXPECT_NEAR(still.face_box.width, 554.256 * 0.17 * 1.1 / 3.0 * 0.5, 2.0);
  EXPECT_NEAR(turning.face_box.x + turning.face_box.width / 2, 320.0, 1.0);  // still centred: the drone looks at them
}

TEST(SyntheticWorld, APersonTurnedAwayShowsTheBackOfTheHeadAndMakesNoGesture) {
  // GIVEN the same person, an arm out, facing the drone and turned 180 deg (turn_deg) with their back to it
  const auto world = [](double turn) {
    return SyntheticWorld(SyntheticParams{}, Scenario::parse("keyframes: [{t: 0, gesture: REST, right_arm: out, turn_deg: " +
                                                                 std::to_string(turn) + "}]\n", "x"), 1);
  };
  cv::Mat facing_labels, away_labels;
  const SyntheticFrame facing = world(0).render(0.5, 0, std::nullopt, &facing_labels);
  const SyntheticFrame away = world(180).render(0.5, 0, std::nullopt, &away_labels);
  // THEN facing, the arm out is OUT; turned away there is no face for a cascade and no gesture, the body box stays
  EXPECT_EQ(facing.truth.expected_kind, hand_obs_t::KIND_OUT);
  EXPECT_GT(facing.truth.face_box.area(), 0.0f);
  EXPECT_EQ(away.truth.face_box.area(), 0.0f);
  EXPECT_EQ(away.truth.expected_kind, hand_obs_t::KIND_NONE);
  EXPECT_EQ(away.truth.expected_mode, gesture_cmd_t::MODE_HOVER);
  EXPECT_NEAR(away.truth.user_box.x, facing.truth.user_box.x, 1.0);
  EXPECT_NEAR(away.truth.user_box.width, facing.truth.user_box.width, 0.02 * facing.truth.user_box.width);
  // AND the head is hair, no face: dark where the facing head is the portrait's skin
  const cv::Mat head_away = away_labels == static_cast<uchar>(PartLabel::Head);
  const cv::Mat head_facing = facing_labels == static_cast<uchar>(PartLabel::Head);
  ASSERT_GT(cv::countNonZero(head_away), 200);
  const cv::Scalar hair = cv::mean(away.bgr, head_away), face = cv::mean(facing.bgr, head_facing);
  EXPECT_LT(hair[2], 80.0);
  EXPECT_GT(face[2], hair[2] + 40.0);
  // AND the arm out shows on the other side of the image: the person's right is the image's right
  EXPECT_LT(facing.truth.right_hand.x, facing.truth.shoulder_centre.x);
  EXPECT_GT(away.truth.right_hand.x, away.truth.shoulder_centre.x);
}

TEST(SyntheticWorld, APersonBehindTheCameraIsNotDrawn) {
  const SyntheticWorld& w = tour_world();
  // GIVEN the drone turned away from the person (yaw 180 deg), and one that flew past them
  for (const CameraPose cam : {CameraPose{0.0, 0.0, -1.5, M_PI}, CameraPose{5.0, 0.0, -1.5, 0.0}}) {
    cv::Mat labels;
    const SyntheticFrame f = w.render(tour_time_of(ground_truth_t::GESTURE_OUT), 0, cam, &labels);
    // THEN no person pixel, empty boxes, no gesture observed
    EXPECT_EQ(cv::countNonZero(labels), 0);
    EXPECT_EQ(f.truth.user_box.area(), 0.0f);
    EXPECT_EQ(f.truth.expected_kind, hand_obs_t::KIND_NONE);
    EXPECT_EQ(f.truth.expected_mode, gesture_cmd_t::MODE_HOVER);
    EXPECT_EQ(f.truth.gesture, ground_truth_t::GESTURE_OUT);
  }
}

TEST(SyntheticWorld, ExpectedCommandsOfTheTourAreItsGestures) {
  const SyntheticWorld& w = tour_world();
  const auto times = w.scenario().key_times();
  for (size_t i = 0; i < times.size(); ++i) {
    const SyntheticTruth t = w.render(times[i], 0, std::nullopt).truth;
    SCOPED_TRACE(std::to_string(times[i]) + " s " + gesture_name(t.gesture));
    switch (t.gesture) {
      case ground_truth_t::GESTURE_REST:
        EXPECT_EQ(t.expected_kind, hand_obs_t::KIND_NONE);
        EXPECT_EQ(t.expected_mode, gesture_cmd_t::MODE_HOVER);
        break;
      case ground_truth_t::GESTURE_OUT:
        EXPECT_EQ(t.expected_kind, hand_obs_t::KIND_OUT);
        EXPECT_EQ(t.expected_mode, gesture_cmd_t::MODE_FINE);
        EXPECT_GT(std::fabs(t.expected_direction.x), 1.0f);  // more than a box width out
        break;
      case ground_truth_t::GESTURE_UP:
        EXPECT_EQ(t.expected_mode, gesture_cmd_t::MODE_UP);
        EXPECT_LT(t.expected_direction.y, 0.0f);
        break;
      case ground_truth_t::GESTURE_DOWN:
        EXPECT_EQ(t.expected_mode, gesture_cmd_t::MODE_DOWN);
        EXPECT_GT(t.expected_direction.y, 0.0f);
        break;
      case ground_truth_t::GESTURE_CLOSER:
        EXPECT_EQ(t.expected_kind, hand_obs_t::KIND_FRONT);
        EXPECT_EQ(t.expected_mode, gesture_cmd_t::MODE_CLOSER);
        EXPECT_FLOAT_EQ(t.expected_direction.z, 1.0f);
        break;
      case ground_truth_t::GESTURE_FURTHER:
        EXPECT_EQ(t.expected_kind, hand_obs_t::KIND_FRONT);
        EXPECT_EQ(t.expected_mode, gesture_cmd_t::MODE_FURTHER);
        EXPECT_FLOAT_EQ(t.expected_direction.z, -1.0f);
        break;
      default:
        ADD_FAILURE() << "unknown gesture";
    }
  }
}

TEST(SyntheticWorld, RendersAreDeterministic) {
  // GIVEN a scene with every per-frame random nuisance on
  const Scenario s = Scenario::parse(
      "keyframes: [{t: 0, noise_sigma: 6, shake_deg: 1, blur_px: 3, jpeg_quality: 70, distractor: true}]\n", "x");
  const SyntheticWorld a(SyntheticParams{}, s, 11), b(SyntheticParams{}, s, 11), c(SyntheticParams{}, s, 12);
  const CameraPose cam{0.5, 0.1, -1.6, 0.05};
  const cv::Mat f1 = a.render(2.0, 50, cam).bgr, f2 = a.render(2.0, 50, cam).bgr, f3 = b.render(2.0, 50, cam).bgr;
  // THEN the same inputs give the same bytes, from the same world and from a second one with the same seed
  EXPECT_EQ(cv::norm(f1, f2, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(f1, f3, cv::NORM_INF), 0.0);
  // and the noise really changes with the frame index and the seed
  EXPECT_GT(cv::norm(f1, a.render(2.0, 51, cam).bgr, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(f1, c.render(2.0, 50, cam).bgr, cv::NORM_L1), 0.0);
}

TEST(SyntheticWorld, MissingDataIsAClearError) {
  SyntheticParams p;
  p.face_image = "no/such/face.png";
  try {
    SyntheticWorld w(p, Scenario::load("tour"), 1);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/face.png"), std::string::npos) << e.what();
  }
}

// The person's colours against the project's trained skin model (data/skin/skin_model.yaml, hands stage):
// hands are skin, clothes are not, and at rest nothing skin-coloured (the hair above the box included) lies
// outside the user box in the hands stage's search rectangle (else Alg. 1 would see a stretched-out hand that is not there).
TEST(SyntheticWorld, SkinModelSeesTheHandsAndNothingElse) {
  const HandsParams hp;
  const SkinClassifier skin(SkinModel::load(resolve_project_path(hp.skin.model)), hp.skin.threshold);
  const SyntheticWorld& w = tour_world();
  cv::Mat labels, mask;
  const SyntheticFrame rest = w.render(tour_time_of(ground_truth_t::GESTURE_REST), 0, std::nullopt, &labels);
  skin.classify(rest.bgr, mask);
  int hand = 0, hand_skin = 0, cloth = 0, cloth_skin = 0, outside_skin = 0;
  const cv::Rect2f& u = rest.truth.user_box;
  const cv::Rect2f roi(u.x - hp.roi_extend_side * u.width, u.y - hp.roi_extend_top * u.height,
                       u.width * (1 + 2 * hp.roi_extend_side), u.height * (1 + hp.roi_extend_top + hp.roi_extend_bottom));
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const auto l = static_cast<PartLabel>(labels.at<uchar>(y, x));
      const bool s = mask.at<uchar>(y, x) != 0;
      const cv::Point2f p(x + 0.5f, y + 0.5f);
      if (l == PartLabel::RightHand || l == PartLabel::LeftHand) ++hand, hand_skin += s;
      if (l == PartLabel::Torso || l == PartLabel::Legs || l == PartLabel::Sleeve) ++cloth, cloth_skin += s;
      if (s && roi.contains(p) && !u.contains(p)) ++outside_skin;
    }
  EXPECT_GT(hand_skin, 0.8 * hand) << hand_skin << " of " << hand;
  EXPECT_LT(cloth_skin, 0.01 * cloth) << cloth_skin << " of " << cloth;
  EXPECT_LE(outside_skin, hp.out_min_skin);
}


// Bystanders (issue 13): GIVEN the shipped `bystander` scenario WHEN the walker is half-way across, 1.6 m from
// the camera, in front of the user (12 s) THEN the walker hides the user's face (its pixels are labelled
// Bystander) while the truth is still the user's, the same as without bystanders; WHEN the waver stands
// beside the user (40 s) THEN they are drawn to the user's right in the image, in their own shirt.
TEST(SyntheticWorld, BystandersAreDrawnFarToNearAndTheTruthStaysTheUsers) {
  const Scenario with = Scenario::load("bystander");
  const SyntheticWorld world(SyntheticParams{}, with, 7);
  // The same user at rest without the bystanders.
  const std::string yaml = "background: " + with.background() + "\nperson: {north: 3.0, east: 0.0}\nkeyframes:\n";
  const SyntheticWorld alone(SyntheticParams{}, Scenario::parse(yaml + "  - {t: 0, gesture: REST}\n", "alone.yaml"), 7);
  cv::Mat labels;
  const SyntheticFrame f = world.render(12.0, 300, std::nullopt, &labels);
  const SyntheticFrame g = alone.render(12.0, 300, std::nullopt);
  EXPECT_EQ(f.truth.user_box, g.truth.user_box);
  EXPECT_EQ(f.truth.face_box, g.truth.face_box);
  const cv::Point face_centre(cvRound(f.truth.face_box.x + f.truth.face_box.width / 2), cvRound(f.truth.face_box.y + f.truth.face_box.height / 2));
  EXPECT_EQ(labels.at<uchar>(face_centre), static_cast<uchar>(PartLabel::Bystander));
  EXPECT_GT(cv::countNonZero(labels == static_cast<uchar>(PartLabel::Bystander)), 20000);  // a big near person

  const SyntheticFrame w = world.render(40.0, 1000, std::nullopt, &labels);
  const cv::Mat by = labels == static_cast<uchar>(PartLabel::Bystander);
  const cv::Rect where = cv::boundingRect(by);
  EXPECT_GT(where.x, f.truth.user_box.x + f.truth.user_box.width);  // beside the user, to the image's right
  EXPECT_GT(cv::countNonZero(by), 3000);
  // Their shirt (BGR 60, 150, 200) on their torso, below their face.
  const cv::Vec3b shirt = w.bgr.at<cv::Vec3b>(where.y + where.height / 3, where.x + where.width / 2);
  EXPECT_NEAR(shirt[2], 200, 90);
  EXPECT_LT(shirt[0], shirt[2]);
}

}  // namespace
}  // namespace gpilot
