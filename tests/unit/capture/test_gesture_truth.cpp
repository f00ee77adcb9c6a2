// The paper's rules on true hand positions (the ground truth's expected observation and command), with
// hand-computed answers on a 100 x 200 px user box at (100, 50): p_uc = (150, 90), p_bc = (150, 150).
#include <gtest/gtest.h>

#include "gesture_truth.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/hand_obs_t.hpp"

namespace gpilot {
namespace {

const cv::Rect2f kBox(100, 50, 100, 200);
const cv::Size kImage(640, 480);
const cv::Point2f kRestRight(120, 200), kRestLeft(180, 200);  // inside the box, below the front band

ExpectedCommand run(cv::Point2f right, cv::Point2f left = kRestLeft) {
  return expected_command(kBox, {right, left}, kImage);
}

TEST(GestureTruth, RestingHandsGiveNoGesture) {
  const ExpectedCommand e = run(kRestRight);
  EXPECT_EQ(e.kind, hand_obs_t::KIND_NONE);
  EXPECT_EQ(e.mode, gesture_cmd_t::MODE_HOVER);
  EXPECT_EQ(e.shoulder_centre, cv::Point2f(150, 90));  // 0.2 of the height
  EXPECT_EQ(e.body_centre, cv::Point2f(150, 150));
}

TEST(GestureTruth, StretchedOutToTheUsersRightIsFineAndNegativeX) {
  // The user's right hand shows on the image's left: x < 0 from p_uc.
  const ExpectedCommand e = run({20, 80});
  EXPECT_EQ(e.kind, hand_obs_t::KIND_OUT);
  EXPECT_EQ(e.vector, cv::Point2f(-130, -10));
  EXPECT_EQ(e.mode, gesture_cmd_t::MODE_FINE);
  EXPECT_FLOAT_EQ(e.direction.x, -1.3f);
  EXPECT_FLOAT_EQ(e.direction.y, -0.1f);
  EXPECT_FLOAT_EQ(e.direction.z, 0.0f);
}

TEST(GestureTruth, RaisedHandSnapsToUpAndLowHandToDown) {
  // |y| = 60 > 0.5 * |x| = 20: x snapped to 0
  ExpectedCommand e = run({190, 30});
  EXPECT_EQ(e.kind, hand_obs_t::KIND_OUT);
  EXPECT_EQ(e.mode, gesture_cmd_t::MODE_UP);
  EXPECT_FLOAT_EQ(e.direction.x, 0.0f);
  EXPECT_FLOAT_EQ(e.direction.y, -0.6f);
  e = run(kRestRight, {230, 200});  // left hand low and out: (80, 110)
  EXPECT_EQ(e.mode, gesture_cmd_t::MODE_DOWN);
  EXPECT_FLOAT_EQ(e.direction.y, 1.1f);
}

TEST(GestureTruth, OfTwoOutstretchedHandsTheFurtherOneWins) {
  // score = |dx| + 0.2 * (p_uc.y - y): right (-100, 0) -> 100; left (+90, -60 up) -> 90 + 12 = 102
  const ExpectedCommand e = run({50, 90}, {240, 30});
  EXPECT_EQ(e.vector, cv::Point2f(90, -60));
}

TEST(GestureTruth, AHandBeyondTheSearchRectangleIsNotSeen) {
  // 0.25 box heights above the box top is y = 0; a hand at y = -10 is outside the rectangle (and the image)
  EXPECT_EQ(run({150, -10}).kind, hand_obs_t::KIND_NONE);
}

TEST(GestureTruth, HandInFrontAboveTheCentreIsCloserBelowIsFurther) {
  ExpectedCommand e = run({155, 120});
  EXPECT_EQ(e.kind, hand_obs_t::KIND_FRONT);
  EXPECT_EQ(e.vector, cv::Point2f(5, -30));
  EXPECT_EQ(e.mode, gesture_cmd_t::MODE_CLOSER);
  EXPECT_FLOAT_EQ(e.direction.z, 1.0f);  // toward the user
  e = run({145, 155});  // band ends at 250 - 0.35 * 200 = 180
  EXPECT_EQ(e.mode, gesture_cmd_t::MODE_FURTHER);
  EXPECT_FLOAT_EQ(e.direction.z, -1.0f);
}

TEST(GestureTruth, FrontHandOutsideTheGateOrTheBandIsNothing) {
  EXPECT_EQ(run({171, 120}).kind, hand_obs_t::KIND_NONE);  // |dx| = 21 >= w/5 = 20
  EXPECT_EQ(run({150, 190}).kind, hand_obs_t::KIND_NONE);  // in the removed legs band
  EXPECT_EQ(run({150, 80}).kind, hand_obs_t::KIND_NONE);   // in the removed face band (top 0.2 = 90)
}

TEST(GestureTruth, AHandUnderTheChinIsNeckAsTheStageSeesItWithTheFaceKnown) {
  // The box's face (7 face heights tall, its top 0.25 face heights below the box's): 28.6 px high from y = 57.1,
  // the neck down to 0.35 face heights below it, y = 95.7: past the 0.2 band (90). A hand at y = 93 is neck to
  // the truth (truth_rules::kNeckInFaces), as to the stage that knows the user's face.
  EXPECT_EQ(run({150, 93}).kind, hand_obs_t::KIND_NONE);
  EXPECT_EQ(run({150, 97}).mode, gesture_cmd_t::MODE_CLOSER);
  EXPECT_EQ(run({150, 97}).vector, cv::Point2f(0, -53));
}

TEST(GestureTruth, WithTheBodyCentreOutOfViewAHandInFrontOrCutByTheBorderIsNotSeen) {
  // GIVEN the box 100 x 200 at (100, 380): p_bc = (150, 480), its 25 px hand square half below the 480 px image
  // (the drone high and close, the hips below the frame), p_uc = (150, 420)
  const cv::Rect2f low(100, 380, 100, 200);
  const cv::Point2f in_front(150, 430), cut_out(40, 475), rest(180, 560);
  // THEN a hand in front is not seen (the stage judges none), nor a hand below the shoulders the bottom cuts
  EXPECT_EQ(expected_command(low, {in_front, rest}, kImage).mode, gesture_cmd_t::MODE_HOVER);
  EXPECT_EQ(expected_command(low, {cut_out, rest}, kImage).kind, hand_obs_t::KIND_NONE);
  // AND a raised hand above the shoulders still is
  EXPECT_EQ(expected_command(low, {cv::Point2f(40, 400), rest}, kImage).kind, hand_obs_t::KIND_OUT);
  // AND a hand is more than its centre: its square (25 px) is cut 8 px at the bottom at the centre (475 - 12 + 25
  // = 488); a 10 px hand's top still has it cut (483), a 20 px hand's (478) does not: that hand is seen
  EXPECT_EQ(expected_command(low, {cut_out, rest}, kImage, 10.0f).kind, hand_obs_t::KIND_NONE);
  EXPECT_EQ(expected_command(low, {cut_out, rest}, kImage, 20.0f).kind, hand_obs_t::KIND_OUT);
  // AND so at the side: a hand at x = 8 has its square cut on the left (8 - 12 < 0) unless it reaches 4 px in
  EXPECT_EQ(expected_command(low, {cv::Point2f(8, 440), rest}, kImage, 6.0f).kind, hand_obs_t::KIND_NONE);
  EXPECT_EQ(expected_command(low, {cv::Point2f(8, 440), rest}, kImage, 8.0f).kind, hand_obs_t::KIND_OUT);
}

}  // namespace
}  // namespace gpilot
