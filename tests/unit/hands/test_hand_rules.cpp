// Our rules on top of the paper's Alg. 1 (hands README, "Hands that are hand-shaped and within reach"), on
// hand-made masks and frames; answers worked out by hand in the comments.
// Box (100, 100, 80, 160): w = 80, hand square 20, p_uc = (140, 132), shoulders at x 112 and 168 (0.35 w),
// reach 1.6 w = 128 px, search rectangle x 4..275, y 60..259.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "hands/hand_detector.hpp"
#include "hands/skin_hand_method.hpp"
#include "paths.hpp"

using namespace gpilot;

namespace {

const cv::Rect2f kBox(100, 100, 80, 160);
const cv::Size kImage(400, 400);
const cv::Scalar kSkin(90, 120, 170), kBlue(200, 60, 20);  // B, G, R: the committed table says 247 and ~0

struct RulesTest : ::testing::Test {
  HandsParams params;
  cv::Mat mask = cv::Mat::zeros(kImage, CV_8UC1);
  HandResult on_mask(const cv::Rect2f& box = kBox) {
    SkinHistogram h(2);
    h.add(0, 0, 0, true);
    h.add(255, 255, 255, false);
    HandDetector d(params, SkinClassifier(SkinModel::train(h, {}), 0.5));
    return d.detect_on_mask(mask, {0, 0}, hand_geometry(params, box, kImage));
  }
  HandResult on_frame(const cv::Mat& frame, const cv::Rect2f& box = kBox) {
    HandDetector d(params, SkinClassifier(SkinModel::load(resolve_project_path(params.skin.model)), params.skin.threshold));
    return d.detect(frame, box);
  }
};

}  // namespace

TEST_F(RulesTest, AForearmHangingBesideTheBodyIsNotStretchedOut) {
  // GIVEN skin at x 96..99, y 200..239, left of the box: from the left shoulder (112, 132) it is 13..16 px out and
  // 68..107 px down, at most atan(16 / 68) = 13.2 deg from straight down (< 15)
  mask(cv::Rect(96, 200, 4, 40)).setTo(1);
  auto r = on_mask();
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.skin_outside, 0);
  // WHEN the rule is off THEN the paper's Alg. 1 takes it for a stretched-out hand (160 pixels > 30)
  params.out_min_angle_deg = 0;
  r = on_mask();
  EXPECT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.skin_outside, 160);
}

TEST_F(RulesTest, AnArmPointingDownAndOutIsStillOut) {
  // GIVEN a hand 60 px out and 80 px below the right shoulder (168, 132): 37 deg from straight down (the DOWN arm)
  mask(cv::Rect(222, 206, 12, 12)).setTo(1);
  const auto r = on_mask();
  EXPECT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.skin_outside, 144);
  EXPECT_GT(r.vector.x, 0);
  EXPECT_GT(r.vector.y, 0);
}

TEST_F(RulesTest, SkinBeyondReachIsNoHand) {
  // GIVEN skin at x 30..39, y 125..134: 73..82 px from the left shoulder (112, 132)
  mask(cv::Rect(30, 125, 10, 10)).setTo(1);
  params.reach_ratio = 0.9;  // 72 px: all of it beyond
  EXPECT_EQ(on_mask().kind, HandKind::None);
  params.reach_ratio = 1.1;  // 88 px: all of it within
  EXPECT_EQ(on_mask().kind, HandKind::Out);
}

TEST_F(RulesTest, ASkinColouredWallBesideTheUserIsNoHandAndAHandIs) {
  // GIVEN a blue frame with a skin-coloured wall patch right of the box: 60 x 100 = 6000 px > 4 hand squares (1600)
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(190, 110, 60, 100), kSkin, cv::FILLED);
  auto r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.blobs_dropped, 1);
  params.max_blob_hand_areas = 0;  // off: the paper's Alg. 1 points at the wall
  EXPECT_EQ(on_frame(frame).kind, HandKind::Out);
  // WHEN a hand-sized patch (15 x 15 = 225 px, the hand square is 400) replaces the wall THEN OUT
  params.max_blob_hand_areas = 4;
  frame.setTo(kBlue);
  cv::rectangle(frame, cv::Rect(230, 120, 15, 15), kSkin, cv::FILLED);
  r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.blobs_dropped, 0);
}

TEST_F(RulesTest, SkinInsideTheBoxIsNotMeasuredAsAWall) {
  // GIVEN a bare torso: skin filling the box between the face and legs bands (80 x 72 = 5760 px > 1600)
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(100, 132, 80, 72), kSkin, cv::FILLED);
  params.front_max_hand_areas = 0;  // (with it, Alg. 2 then drops the torso as no hand: the test above)
  const auto r = on_frame(frame);
  EXPECT_EQ(r.blobs_dropped, 0);
  EXPECT_EQ(r.skin_inside, 80 * 72);
}

TEST(SkinHandMethod, TheBoxIsTheTrackersEvenWithAFaceAndANewTrackForgetsTheUser) {
  // GIVEN a face 32 x 32 at (124, 108), whose preset head-body ratios would make the box 88 x 224 at (96, 100)
  HandsParams p;
  const SkinModel model = SkinModel::load(resolve_project_path(p.skin.model));
  SkinHandMethod o(p, model);
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(124, 108, 32, 32), kSkin, cv::FILLED);
  // WHEN the tracker's box comes with it THEN the stage works on the tracker's box, and learns the face's skin
  auto r = o.detect(frame, UserView{kBox, cv::Rect2f(124, 108, 32, 32), 1});
  EXPECT_EQ(r.geometry.box, cv::Rect(100, 100, 80, 160));
  EXPECT_EQ(o.adaptation().user_samples, 20 * 11);  // cheek band: x 130..149 (124 + 0.2 and 0.8 of 32, rounded), y 124..134
  // WHEN the next frame has no face THEN the same box, and what was learnt stays
  r = o.detect(frame, UserView{kBox, std::nullopt, 1});
  EXPECT_EQ(r.geometry.box, cv::Rect(100, 100, 80, 160));
  EXPECT_EQ(o.adaptation().user_samples, 20 * 11);
  // WHEN a new track starts THEN it is forgotten
  o.detect(frame, UserView{kBox, std::nullopt, 2});
  EXPECT_EQ(o.adaptation().user_samples, 0);
}

TEST_F(RulesTest, AForearmHangingAtTheTorsosEdgeIsNotAHandInFront) {
  // GIVEN skin 8 x 54 at x 152..159, y 150..203 inside the box: its inner edge 12 px from p_bc.x (< w/5 = 16),
  // 6.75 times taller than wide, reaching below the body centre (y 180): a bare forearm hanging at the torso
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(152, 150, 8, 54), kSkin, cv::FILLED);
  auto r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.upright_dropped, 1);
  params.front_max_upright = 0;  // off: the paper's Alg. 2 takes it for a hand in front
  r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::Front);
  EXPECT_EQ(r.hand.x, 152);
  // WHEN a compact hand (12 x 12) is in front of the chest instead THEN FRONT, higher
  params.front_max_upright = 2.5;
  frame.setTo(kBlue);
  cv::rectangle(frame, cv::Rect(134, 150, 12, 12), kSkin, cv::FILLED);
  r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::Front);
  EXPECT_LT(r.vector.y, 0);
  EXPECT_EQ(r.upright_dropped, 0);
}

TEST_F(RulesTest, AfterThreeHangingForearmsAlg2GivesUpAndSaysSo) {
  // GIVEN three forearms 8 x 54 at x 126, 137 and 148 (y 150..203), each its own skin component, each within w/5
  // = 16 px of p_bc.x = 140 and reaching below the body centre (y 180): Alg. 2 takes one, drops it as hanging,
  // looks again, three times (kMaxDroppedCandidates)
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  for (int x : {126, 137, 148}) cv::rectangle(frame, cv::Rect(x, 150, 8, 54), kSkin, cv::FILLED);
  // WHEN the detector looks
  const HandResult r = on_frame(frame);
  // THEN it gives up on the frame: no hand, no skin counts (as HAND_OBS had them), and the three dropped counted
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.hand_skin, 0);
  EXPECT_EQ(r.skin_inside, 0);
  EXPECT_EQ(r.upright_dropped, 3);
  EXPECT_EQ(r.geometry.box, cv::Rect(100, 100, 80, 160));
  // AND with two of them it takes neither and has looked at both
  frame.setTo(kBlue);
  for (int x : {126, 148}) cv::rectangle(frame, cv::Rect(x, 150, 8, 54), kSkin, cv::FILLED);
  const HandResult two = on_frame(frame);
  EXPECT_EQ(two.kind, HandKind::None);
  EXPECT_EQ(two.upright_dropped, 2);
}

TEST_F(RulesTest, ATorsoSizedSkinRegionIsTheShirtNotAHandInFront) {
  // GIVEN skin 40 x 40 at x 120..159, y 140..179 inside the box (an orange shirt the table calls skin): 1600 px,
  // 4 hand squares of 20 x 20 exactly -> kept at 4, dropped when one more row is skin (1640 > 1600)
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(120, 140, 40, 41), kSkin, cv::FILLED);
  auto r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.upright_dropped, 1);
  params.front_max_hand_areas = 0;  // off: the paper's Alg. 2 takes the shirt for a hand in front
  r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::Front);
  params.front_max_hand_areas = 4;
  frame.setTo(kBlue);
  cv::rectangle(frame, cv::Rect(120, 140, 40, 40), kSkin, cv::FILLED);
  r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::Front);
  EXPECT_EQ(r.upright_dropped, 0);
}

TEST_F(RulesTest, AHandInFrontIsNotJudgedWhileTheBodyCentreIsOutOfTheImage) {
  // GIVEN skin at x 132..147, y 150..165 in the box, centred on p_bc.x = 140 and above p_bc.y = 180: a hand in
  // front, higher (256 pixels, F_skin 256 > 30, |dx| < w/5 = 16)
  const cv::Rect hand(132, 150, 16, 16);
  mask(hand).setTo(1);
  auto r = on_mask();
  EXPECT_EQ(r.kind, HandKind::Front);
  EXPECT_LT(r.vector.y, 0);
  EXPECT_FALSE(r.front_out_of_view);
  // WHEN the frame ends at row 185, above p_bc + half a hand square (180 + 10): the drone high and close, the
  // user's hips below the frame. THEN a hand at the bottom edge cannot be told higher from lower: no hand
  const cv::Size cut(400, 185);
  SkinHistogram h(2);
  h.add(0, 0, 0, true);
  h.add(255, 255, 255, false);
  HandDetector d(params, SkinClassifier(SkinModel::train(h, {}), 0.5));
  const cv::Mat cut_mask = mask(cv::Rect(0, 0, cut.width, cut.height)).clone();
  r = d.detect_on_mask(cut_mask, {0, 0}, hand_geometry(params, kBox, cut));
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_TRUE(r.front_out_of_view);
  // AND with the rule off THEN the paper's Alg. 2 reads it as higher (CLOSER)
  params.needs_body_centre = false;
  HandDetector paper(params, SkinClassifier(SkinModel::train(h, {}), 0.5));
  r = paper.detect_on_mask(cut_mask, {0, 0}, hand_geometry(params, kBox, cut));
  EXPECT_EQ(r.kind, HandKind::Front);
  EXPECT_LT(r.vector.y, 0);
}

TEST_F(RulesTest, AnArmMustReachTheTorsoNotTheBoxMarginBesideIt) {
  // GIVEN a green shirt on the torso (the box less 0.2 w = 16 px each side: x 116..163, rows 132..179) and a
  // hand-sized skin patch right of the box (x 190..204, y 150..164) joined by a skin strip (x 170..189, y 155..158)
  // that ends in the box's right margin, 6 px short of the shirt: a skin-coloured thing beside the user that
  // touches the box, not an arm (the arm closing, 2 r = 4 px, does not bridge 6)
  const cv::Scalar kGreen(60, 140, 40);
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(116, 132, 48, 48), kGreen, cv::FILLED);
  cv::rectangle(frame, cv::Rect(190, 150, 15, 15), kSkin, cv::FILLED);
  cv::rectangle(frame, cv::Rect(170, 155, 20, 4), kSkin, cv::FILLED);
  auto r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_GE(r.armless_dropped, 1);
  // WHEN the torso is the whole box width (inset 0) THEN the strip reaches it and the patch is taken for a hand
  params.torso_inset_ratio = 0;
  r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::Out);
  // AND WHEN the strip reaches the shirt (an arm) THEN OUT with the inset too
  params.torso_inset_ratio = 0.2;
  cv::rectangle(frame, cv::Rect(160, 155, 30, 4), kSkin, cv::FILLED);
  r = on_frame(frame);
  EXPECT_EQ(r.kind, HandKind::Out);
  EXPECT_GT(r.vector.x, 0);
}

TEST_F(RulesTest, AHandCutByTheBorderBelowTheShouldersIsNotJudgedWhileTheBodyIsCut) {
  // GIVEN the frame ending at row 185 (p_bc.y 180 + 10 is out of it) and skin right of the box at x 190..204,
  // y 176..184, touching the bottom border: below the right shoulder (168, 132), 22..36 px out and 44..52 px
  // down (most of it over 25 deg from straight down, within reach): the 20 px hand square at any of its pixels
  // reaches row 186 or lower, past the border
  const cv::Size cut(400, 185);
  cv::Mat m = cv::Mat::zeros(cut, CV_8UC1);
  m(cv::Rect(190, 176, 15, 9)).setTo(1);
  SkinHistogram h(2);
  h.add(0, 0, 0, true);
  h.add(255, 255, 255, false);
  auto run = [&]() {
    HandDetector d(params, SkinClassifier(SkinModel::train(h, {}), 0.5));
    return d.detect_on_mask(m, {0, 0}, hand_geometry(params, kBox, cut));
  };
  EXPECT_EQ(run().kind, HandKind::None);
  // WHEN the whole frame is seen (400 rows: the body centre in view) THEN the same skin is an OUT hand
  const cv::Mat cut_mask = m;
  m = cv::Mat::zeros(kImage, CV_8UC1);
  cut_mask.copyTo(m(cv::Rect(0, 0, cut.width, cut.height)));
  HandDetector whole(params, SkinClassifier(SkinModel::train(h, {}), 0.5));
  EXPECT_EQ(whole.detect_on_mask(m, {0, 0}, hand_geometry(params, kBox, kImage)).kind, HandKind::Out);
  // AND with the rule off THEN the paper's Alg. 1 takes the cut one too
  m = cut_mask;
  params.needs_body_centre = false;
  EXPECT_EQ(run().kind, HandKind::Out);
}

TEST_F(RulesTest, ABoxMostlyAboveTheFrameHasNoTorsoAndNoArm) {
  // GIVEN the box (100, -100, 80, 160): p_uc y -68, p_bc y -20, only rows 0..59 in the frame, so the torso
  // (face rows end -68 .. body centre -20) is wholly above the image; and skin right of the box at x 220..234,
  // y 20..34: from the right shoulder (168, -68) 52..66 px out, 88..102 px down (27..37 deg), within reach
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(220, 20, 15, 15), kSkin, cv::FILLED);
  HandDetector d(params, SkinClassifier(SkinModel::load(resolve_project_path(params.skin.model)), params.skin.threshold));
  const HandResult r = d.detect(frame, cv::Rect2f(100, -100, 80, 160));
  // THEN no arm can reach a torso out of view: the candidate is dropped, nothing is read above row 0
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_GE(r.armless_dropped, 1);
  // AND the same skin with the box in the frame is an OUT hand (the candidate itself is fine), when an arm joins it
  params.arm_connected = false;
  HandDetector plain(params, SkinClassifier(SkinModel::load(resolve_project_path(params.skin.model)), params.skin.threshold));
  EXPECT_EQ(plain.detect(frame, cv::Rect2f(100, -100, 80, 160)).kind, HandKind::Out);
}

// A user 10 m away (the e2e `far` run): box (150, 150, 30, 77), hand square round(7.5) = 8 px, p_uc (165, 165.4),
// p_bc (165, 188.5), torso x 156..173 (inset round(6)), rows 165..188, search rectangle from x 114, skin opening
// radius round(0.75) = 1 (3x3), arm closing radius 1.
const cv::Rect2f kFarBox(150, 150, 30, 77);

TEST_F(RulesTest, AFarUsersSmallHandInFrontIsSeen) {
  // GIVEN a 4x5 hand (20 skin pixels) at the body centre: the paper's 30 px is a third of this user's 8x8 hand
  // square, so min_skin_square_share caps it at 0.25 x 64 = 16
  cv::rectangle(mask, cv::Rect(163, 180, 4, 5), cv::Scalar(255), cv::FILLED);
  auto r = on_mask(kFarBox);
  ASSERT_EQ(r.kind, HandKind::Front);
  EXPECT_EQ(r.hand_skin, 20);
  // WHEN the paper's count alone is asked (share 0) THEN no hand
  params.min_skin_square_share = 0;
  EXPECT_EQ(on_mask(kFarBox).kind, HandKind::None);
  // AND a near user keeps the paper's 30: 20 pixels in front of the 80 px box (a 20 px square, 0.25 x 400 = 100)
  params.min_skin_square_share = 0.25;
  mask.setTo(0);
  cv::rectangle(mask, cv::Rect(138, 175, 4, 5), cv::Scalar(255), cv::FILLED);
  EXPECT_EQ(on_mask().kind, HandKind::None);
}

TEST_F(RulesTest, AFarUsersDownHandIsOutWhereTheAngleRuleLeavesLittleOfIt) {
  // GIVEN the far box's DOWN hand with its forearm opened away and its side nearer the body under
  // out_min_angle_deg: a 3x4 hand (12 px) 15.5..17.5 px right of and 26.6..29.6 px below the right shoulder
  // (175.5, 165.4), 28..33 deg from straight down, within reach (a CI far run at 9.9 m: 11-17 px outside the box)
  mask(cv::Rect(191, 192, 3, 4)).setTo(1);
  auto r = on_mask(kFarBox);
  // THEN OUT, down and out: below the shoulder line Alg. 1 asks more than 0.15 x 64 = 9.6, so 9 px
  ASSERT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.skin_outside, 12);
  EXPECT_GT(r.vector.x, 0);
  EXPECT_GT(r.vector.y, 0);
  // AND WHEN it asks the quarter it asks elsewhere (16 px) THEN it is lost, as in that run
  params.down_min_skin_square_share = 0;
  EXPECT_EQ(on_mask(kFarBox).kind, HandKind::None);
  // AND the same 12 px above the shoulder line (out and up) are not enough: 16 there
  params.down_min_skin_square_share = 0.15;
  mask.setTo(0);
  mask(cv::Rect(191, 150, 3, 4)).setTo(1);
  EXPECT_EQ(on_mask(kFarBox).kind, HandKind::None);
  // AND a 3x3 speckle (9 px) below it is not enough either
  mask.setTo(0);
  mask(cv::Rect(191, 192, 3, 3)).setTo(1);
  EXPECT_EQ(on_mask(kFarBox).kind, HandKind::None);
}

TEST_F(RulesTest, AFarUsersTwoPixelArmJoinsTheHandToTheTorso) {
  // GIVEN a green shirt filling the far box's torso rows, a 6x6 hand 27 px left of the box (x 118..123, y 162..167)
  // and a forearm 2 px thick from the hand to the shirt (x 124..149, y 164..165)
  const cv::Scalar kGreen(60, 140, 40);
  cv::Mat frame(kImage, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(150, 165, 30, 24), kGreen, cv::FILLED);
  cv::rectangle(frame, cv::Rect(118, 162, 6, 6), kSkin, cv::FILLED);
  cv::rectangle(frame, cv::Rect(124, 164, 26, 2), kSkin, cv::FILLED);
  // WHEN the stage runs THEN OUT: the 3x3 opening clears the forearm from the hand candidates, but the arm test
  // reads the skin before it (on the opened mask the 26 px gap left the hand armless and the frame NONE)
  const auto r = on_frame(frame, kFarBox);
  ASSERT_EQ(r.kind, HandKind::Out);
  EXPECT_LT(r.vector.x, -30);
  EXPECT_EQ(r.armless_dropped, 0);
  // AND WHEN the forearm is cut (a 6 px gap at x 136..141) THEN the hand is armless, as before
  cv::rectangle(frame, cv::Rect(136, 164, 6, 2), kBlue, cv::FILLED);
  EXPECT_EQ(on_frame(frame, kFarBox).kind, HandKind::None);
}
