// The keypoint truth rules on hand-made people (image pixels, y down; the person faces the camera, so their
// left shoulder is on the image's right).
#include <gtest/gtest.h>

#include "keypoint_truth.hpp"
#include "test_people.hpp"

namespace gpilot {
namespace {

using test_people::arm;
using test_people::upright;

TEST(KeypointTruth, GivenArmsHangingStraightWhenClassifiedThenBothRestAndPersonRest) {
  const PersonKeypointTruth t = keypoint_truth(upright());
  ASSERT_TRUE(t.usable);
  EXPECT_EQ(t.left.label, ArmTruth::Rest);
  EXPECT_EQ(t.right.label, ArmTruth::Rest);
  EXPECT_EQ(t.person, PersonTruth::Rest);
  EXPECT_FLOAT_EQ(t.torso_centre.x, 100.0f);
  EXPECT_FLOAT_EQ(t.torso_centre.y, 140.0f);
  EXPECT_DOUBLE_EQ(t.torso_height, 80.0);
  EXPECT_DOUBLE_EQ(t.span_min_x, 72.0);
  EXPECT_DOUBLE_EQ(t.span_max_x, 128.0);
}

TEST(KeypointTruth, GivenLeftArmStraightSidewaysWhenClassifiedThenOutAndPersonOut) {
  BodyKeypoints k = upright();
  arm(k.left_elbow, k.left_wrist, {150, 100}, {180, 102});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_EQ(t.left.label, ArmTruth::Out);
  EXPECT_NEAR(t.left.angle_from_down_deg, 88.1, 0.1);
  EXPECT_GT(t.left.straightness, 0.99);
  EXPECT_EQ(t.right.label, ArmTruth::Rest);
  EXPECT_EQ(t.person, PersonTruth::Out);
}

TEST(KeypointTruth, GivenRightArmStraightUpWhenClassifiedThenOut) {
  BodyKeypoints k = upright();
  arm(k.right_elbow, k.right_wrist, {75, 70}, {70, 40});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_EQ(t.right.label, ArmTruth::Out);
  EXPECT_TRUE(t.right.wrist_above_shoulder_line);
  EXPECT_GT(t.right.angle_from_down_deg, 170.0);
  EXPECT_EQ(t.person, PersonTruth::Out);
}

TEST(KeypointTruth, GivenStraightArm40DegFromDownWhenClassifiedThenRestNotOut) {
  BodyKeypoints k = upright();
  // W - S = (40, 47.7): 40 deg from down, straight, wrist below the torso centre.
  arm(k.left_elbow, k.left_wrist, {140, 123.8}, {160, 147.7});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_NEAR(t.left.angle_from_down_deg, 40.0, 0.1);
  EXPECT_EQ(t.left.label, ArmTruth::Rest);
}

TEST(KeypointTruth, GivenStraightHangingWristInsideTheTorsoSpanWhenClassifiedThenRestBeforeFront) {
  BodyKeypoints k = upright();
  // Wrist within the torso span and above the hip line (FRONT_LOW by rule 3) but the arm is straight and hangs.
  arm(k.left_elbow, k.left_wrist, {124, 140}, {127, 175});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_TRUE(t.left.wrist_in_torso_span);
  EXPECT_FALSE(t.left.wrist_below_hip_line);
  EXPECT_EQ(t.left.label, ArmTruth::Rest);
  EXPECT_STREQ(t.left.reason, "straight arm hanging");
}

TEST(KeypointTruth, GivenBentArmWristOverUpperTorsoWhenClassifiedThenFrontHigh) {
  BodyKeypoints k = upright();
  arm(k.left_elbow, k.left_wrist, {130, 140}, {105, 120});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_LT(t.left.straightness, 0.85);
  EXPECT_EQ(t.left.label, ArmTruth::FrontHigh);
  EXPECT_EQ(t.person, PersonTruth::Front);
}

TEST(KeypointTruth, GivenBentArmWristOverLowerTorsoWhenClassifiedThenFrontLow) {
  BodyKeypoints k = upright();
  arm(k.right_elbow, k.right_wrist, {65, 140}, {95, 160});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_EQ(t.right.label, ArmTruth::FrontLow);
  EXPECT_EQ(t.person, PersonTruth::Front);
}

TEST(KeypointTruth, GivenOneArmOutAndOneFrontWhenClassifiedThenPersonAmbiguous) {
  BodyKeypoints k = upright();
  arm(k.left_elbow, k.left_wrist, {150, 100}, {180, 102});
  arm(k.right_elbow, k.right_wrist, {65, 140}, {95, 160});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_EQ(t.left.label, ArmTruth::Out);
  EXPECT_TRUE(is_front(t.right.label));
  EXPECT_EQ(t.person, PersonTruth::Ambiguous);
}

TEST(KeypointTruth, GivenBentArmWristBelowTheHipLineWhenClassifiedThenRest) {
  BodyKeypoints k = upright();
  arm(k.left_elbow, k.left_wrist, {160, 130}, {130, 190});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_LT(t.left.straightness, 0.85);
  EXPECT_EQ(t.left.label, ArmTruth::Rest);
  EXPECT_STREQ(t.left.reason, "wrist below hip line");
}

TEST(KeypointTruth, GivenHandAtTheFaceWhenClassifiedThenAmbiguousAndPersonAmbiguous) {
  BodyKeypoints k = upright();
  // Head bowed: face points low, the face box (grown) reaches below the shoulder line, where the wrist is.
  for (BodyPoint* p : {&k.nose, &k.left_eye, &k.right_eye, &k.left_ear, &k.right_ear}) p->p.y += 30;
  arm(k.left_elbow, k.left_wrist, {135, 140}, {100, 110});
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_TRUE(t.left.wrist_at_face);
  EXPECT_EQ(t.left.label, ArmTruth::Ambiguous);
  EXPECT_STREQ(t.left.reason, "wrist at the face");
  EXPECT_EQ(t.person, PersonTruth::Ambiguous);

  // The same wrist with no face point labelled: nothing is at the face, so FRONT_HIGH.
  for (BodyPoint* p : {&k.nose, &k.left_eye, &k.right_eye, &k.left_ear, &k.right_ear}) p->v = 0;
  const PersonKeypointTruth no_face = keypoint_truth(k);
  EXPECT_FALSE(no_face.face_box.has_value());
  EXPECT_EQ(no_face.left.label, ArmTruth::FrontHigh);
}

TEST(KeypointTruth, GivenWristJustOutsideTheGrownFaceBoxWhenClassifiedThenNotAtTheFace) {
  BodyKeypoints k = upright();
  for (BodyPoint* p : {&k.nose, &k.left_eye, &k.right_eye, &k.left_ear, &k.right_ear}) p->p.y += 30;
  // Face box y 85.2..115.1, h 29.9: grown to 79.2..121.1 (each side + 0.2 h); x grown 83.9..116.1.
  arm(k.left_elbow, k.left_wrist, {135, 140}, {117, 110});
  EXPECT_FALSE(keypoint_truth(k).left.wrist_at_face);
  arm(k.left_elbow, k.left_wrist, {135, 140}, {115.5f, 110});
  EXPECT_TRUE(keypoint_truth(k).left.wrist_at_face);
}

TEST(KeypointTruth, GivenFacePointsWhenFaceBoxMadeThenTheSharedSetsFormula) {
  const auto f = keypoint_face_box(upright());
  ASSERT_TRUE(f.has_value());
  // x-extent 90..110 -> width max(1.15 * 20, 0.45 * 40 (shoulder width in x)) = 23, height 29.9, centre (100, 67.2 + 2.99).
  EXPECT_NEAR(f->width, 23.0, 1e-4);
  EXPECT_NEAR(f->height, 29.9, 1e-4);
  EXPECT_NEAR(f->x, 88.5, 1e-4);
  EXPECT_NEAR(f->y, 67.2 + 2.99 - 14.95, 1e-4);
}

TEST(KeypointTruth, GivenAHiddenWristWhenClassifiedThenSkippedWithTheKeypointNamed) {
  BodyKeypoints k = upright();
  k.left_wrist.v = 1;
  k.right_hip.v = 0;
  const PersonKeypointTruth t = keypoint_truth(k);
  EXPECT_FALSE(t.usable);
  EXPECT_NE(t.skip_reason.find("left_wrist v=1"), std::string::npos) << t.skip_reason;
  EXPECT_NE(t.skip_reason.find("right_hip v=0"), std::string::npos) << t.skip_reason;
}

TEST(KeypointTruth, GivenAHiddenNoseWhenClassifiedThenStillUsable) {
  BodyKeypoints k = upright();
  k.nose.v = 0;
  EXPECT_TRUE(keypoint_truth(k).usable);
}

TEST(KeypointTruth, GivenArmLabelsWhenCombinedThenThePersonRule) {
  EXPECT_EQ(person_truth(ArmTruth::Out, ArmTruth::Ambiguous), PersonTruth::Out);
  EXPECT_EQ(person_truth(ArmTruth::FrontLow, ArmTruth::Ambiguous), PersonTruth::Front);
  EXPECT_EQ(person_truth(ArmTruth::Rest, ArmTruth::FrontHigh), PersonTruth::Front);
  EXPECT_EQ(person_truth(ArmTruth::Rest, ArmTruth::Rest), PersonTruth::Rest);
  EXPECT_EQ(person_truth(ArmTruth::Rest, ArmTruth::Ambiguous), PersonTruth::Ambiguous);
  // Two commanding arms: none of the paper's one-armed gestures.
  EXPECT_EQ(person_truth(ArmTruth::Out, ArmTruth::Out), PersonTruth::Ambiguous);
  EXPECT_EQ(person_truth(ArmTruth::FrontHigh, ArmTruth::FrontLow), PersonTruth::Ambiguous);
  EXPECT_EQ(person_truth(ArmTruth::Out, ArmTruth::FrontHigh), PersonTruth::Ambiguous);
}

TEST(KeypointTruth, GivenCocoNamesWhenFilledByNameThenEachPointInItsPlace) {
  const BodyKeypoints k = BodyKeypoints::from([](const std::string& name) -> std::optional<BodyPoint> {
    if (name == "left_wrist") return BodyPoint{{1, 2}, 2};
    if (name == "right_hip") return BodyPoint{{3, 4}, 1};
    return std::nullopt;
  });
  EXPECT_EQ(k.left_wrist.p, cv::Point2f(1, 2));
  EXPECT_EQ(k.right_hip.v, 1);
  EXPECT_EQ(k.left_shoulder.v, 0);
}

}  // namespace
}  // namespace gpilot
