// The paper's Alg. 1 and Alg. 2 on hand-made skin masks, answers worked out by hand in the comments.
// Box (100, 100, 80, 160): w = 80, hand square 20 (half 10), p_uc = (140, 132), p_bc = (140, 180), w/5 = 16.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "hands/hand_detector.hpp"
#include "paths.hpp"

using namespace gpilot;

namespace {

const cv::Rect2f kBox(100, 100, 80, 160);
const cv::Size kImage(400, 400);

SkinClassifier any_classifier() {
  SkinHistogram h(2);
  h.add(0, 0, 0, true);
  h.add(255, 255, 255, false);
  return SkinClassifier(SkinModel::train(h, {}), 0.5);
}

struct Fixture : ::testing::Test {
  HandsParams params;
  cv::Mat mask = cv::Mat::zeros(kImage, CV_8UC1);
  HandResult run() {
    HandDetector d(params, any_classifier());
    return d.detect_on_mask(mask, {0, 0}, hand_geometry(params, kBox, kImage));
  }
  void fill(int x, int y, int w, int h) { mask(cv::Rect(x, y, w, h)).setTo(255); }
};

}  // namespace

TEST_F(Fixture, GeometryFollowsThePaper) {
  const auto g = hand_geometry(params, kBox, kImage);
  EXPECT_TRUE(g.valid);
  EXPECT_EQ(g.hand_side, 20);
  EXPECT_FLOAT_EQ(g.shoulder_centre.x, 140);
  EXPECT_FLOAT_EQ(g.shoulder_centre.y, 132);
  EXPECT_FLOAT_EQ(g.body_centre.y, 180);
  EXPECT_EQ(g.roi, cv::Rect(4, 60, 272, 200));  // 1.2 w each side, 0.25 h above
  EXPECT_EQ(g.face_rows_end, 132);
  EXPECT_EQ(g.legs_rows_begin, 204);
}

TEST_F(Fixture, EmptyMaskIsNone) {
  const auto r = run();
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.skin_outside, 0);
  EXPECT_EQ(r.vector, cv::Point2f(0, 0));
}

TEST_F(Fixture, Alg1NeedsMoreThan30SkinPixelsOutside) {
  fill(20, 130, 5, 6);  // exactly 30 outside: not more than 30, and nothing inside for Alg. 2
  auto r = run();
  EXPECT_EQ(r.skin_outside, 30);
  EXPECT_EQ(r.kind, HandKind::None);
  // GIVEN a 31st pixel at (19, 133): every pixel's square covers all 31, F = 31, so the score is
  // |140 - x| + 0.2 (132 - y) + 15.5: (19, 133) gives 121 - 0.2 = 120.8 > (20, 130) with 120 + 0.4.
  mask.at<uint8_t>(133, 19) = 255;
  r = run();
  EXPECT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.hand, cv::Point(19, 133));
  EXPECT_EQ(r.hand_skin, 31);
  EXPECT_FLOAT_EQ(r.vector.x, -121);
  EXPECT_FLOAT_EQ(r.vector.y, 1);
  EXPECT_EQ(r.hand_box, cv::Rect(9, 123, 20, 20));
}

TEST_F(Fixture, MirrorUserPointingToTheirRightGivesNegativeX) {
  // The user faces the camera: their right hand, stretched to their right, is on the image's left.
  fill(30, 125, 10, 10);
  const auto r = run();
  ASSERT_EQ(r.kind, HandKind::Out);
  EXPECT_LT(r.vector.x, 0);
  // And the other arm, to the user's left, is on the image's right: x > 0.
  mask.setTo(0);
  fill(240, 125, 10, 10);
  const auto l = run();
  ASSERT_EQ(l.kind, HandKind::Out);
  EXPECT_GT(l.vector.x, 0);
}

TEST_F(Fixture, Alg1Lambda2PrefersTheRaisedArm) {
  // A at (30, 60): 110 across, 72 above p_uc. B at (20, 132): 120 across, level with p_uc. Each alone in its
  // square (F = 1). A filler block of 36 at (230..235, 140..145) makes the count pass and scores at most
  // 95 - 1.6 + 18 = 111.4 (113 with λ2 = 0), below both.
  mask.at<uint8_t>(60, 30) = 255;
  mask.at<uint8_t>(132, 20) = 255;
  fill(230, 140, 6, 6);
  // λ2 = 0.2: A = 110 + 14.4 + 0.5 = 124.9 beats B = 120 + 0 + 0.5.
  auto r = run();
  ASSERT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.hand, cv::Point(30, 60));
  EXPECT_FLOAT_EQ(r.vector.x, -110);
  EXPECT_FLOAT_EQ(r.vector.y, -72);
  // λ2 = 0: B (120.5) beats A (110.5).
  params.lambda2 = 0;
  r = run();
  EXPECT_EQ(r.hand, cv::Point(20, 132));
}

TEST_F(Fixture, Alg1Lambda1PrefersTheDenseBlob) {
  // A 10x10 block at x 60..69 (F up to 100 at its centre) against a lone pixel further out at (10, 132).
  // Lone pixel: 130 + 0 + 0.5 = 130.5. Block pixel (64, 127): F = 100 (square 54..73 x 117..136 holds all),
  // 76 + 1 + 50 = 127; (60, 125) has F = 100 too: 80 + 1.4 + 50 = 131.4, the best in the block.
  fill(60, 125, 10, 10);
  mask.at<uint8_t>(132, 10) = 255;
  auto r = run();
  ASSERT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.hand, cv::Point(60, 125));
  EXPECT_EQ(r.hand_skin, 100);
  params.lambda1 = 0;  // distance only: the lone pixel
  r = run();
  EXPECT_EQ(r.hand, cv::Point(10, 132));
}

TEST_F(Fixture, Alg2FrontHandInsideTheGate) {
  // 6x6 block at x 152..157, y 200..205: F = 36 everywhere in it; score -|140 - x| + 0.468, best at x = 152
  // (dx 12 < 16), first row wins the tie: (152, 200) -> vector (12, 20): below p_bc (lower).
  fill(152, 200, 6, 6);
  const auto r = run();
  ASSERT_EQ(r.kind, HandKind::Front);
  EXPECT_EQ(r.hand, cv::Point(152, 200));
  EXPECT_EQ(r.hand_skin, 36);
  EXPECT_FLOAT_EQ(r.vector.x, 12);
  EXPECT_FLOAT_EQ(r.vector.y, 20);
  EXPECT_EQ(r.skin_inside, 36);
}

TEST_F(Fixture, Alg2HigherHandHasNegativeY) {
  fill(130, 150, 6, 6);  // columns 130..135: best x = 135 (dx 5), first row y = 150: vector (-5, -30)
  const auto r = run();
  ASSERT_EQ(r.kind, HandKind::Front);
  EXPECT_FLOAT_EQ(r.vector.x, -5);
  EXPECT_FLOAT_EQ(r.vector.y, -30);
}

TEST_F(Fixture, Alg2WidthGateIsStrict) {
  fill(156, 200, 6, 6);  // nearest column 156: |dx| = 16, not < w/5 = 16
  EXPECT_EQ(run().kind, HandKind::None);
  mask.setTo(0);
  fill(155, 200, 6, 6);  // 15 < 16
  EXPECT_EQ(run().kind, HandKind::Front);
}

TEST_F(Fixture, Alg2NeedsMoreThan30InTheSquare) {
  fill(140, 200, 5, 6);  // F = 30: not more than 30
  auto r = run();
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.front_candidate_skin, 30);
  mask.at<uint8_t>(203, 139) = 255;  // 31: dx of (140, 200) is 0, score 0 + 0.403 is the best
  r = run();
  ASSERT_EQ(r.kind, HandKind::Front);
  EXPECT_EQ(r.hand, cv::Point(140, 200));
}

TEST_F(Fixture, Alg2ArgmaxComesBeforeTheGates) {
  // A lone pixel at dx 0 scores 0.013 and beats a 10x10 block at dx >= 5 (-5 + 1.3): its F = 1 then fails the
  // 30-pixel gate and the frame is NONE, exactly as the paper's Alg. 2 is written.
  fill(145, 200, 10, 10);
  mask.at<uint8_t>(150, 140) = 255;
  EXPECT_EQ(run().kind, HandKind::None);
}

TEST_F(Fixture, Alg1ComesFirst) {
  fill(152, 200, 6, 6);  // a valid front hand
  fill(20, 130, 8, 8);   // and 64 pixels outside
  EXPECT_EQ(run().kind, HandKind::Out);
}

TEST(HandGeometry, BadBoxesAreInvalid) {
  HandsParams p;
  EXPECT_FALSE(hand_geometry(p, {0, 0, 0, 10}, kImage).valid);
  EXPECT_FALSE(hand_geometry(p, {NAN, 0, 10, 10}, kImage).valid);
  EXPECT_FALSE(hand_geometry(p, {1000, 1000, 50, 50}, kImage).valid);  // off the image
  HandDetector d(p, any_classifier());
  const cv::Mat frame(kImage, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_EQ(d.detect(frame, {1000, 1000, 50, 50}).kind, HandKind::None);
}

// The USER_TRACK box of 1e6 px (hands stalled 5.4 s, +545 MB): the sizes taken from the box are capped
// at the image, where a larger kernel or square changes nothing, so the frame costs what any frame costs.
TEST(HandGeometry, AHugeBoxSizesNothingBeyondTheImage) {
  HandsParams p;
  const HandGeometry g = hand_geometry(p, {0, 0, 1e6f, 1e6f}, kImage);
  ASSERT_TRUE(g.valid);
  EXPECT_EQ(g.box, cv::Rect(0, 0, 400, 400));
  EXPECT_EQ(g.roi, cv::Rect(0, 0, 400, 400));
  EXPECT_EQ(g.open_radius, 400);    // 0.025 x 1e6 = 25000 uncapped
  EXPECT_EQ(g.hand_side, 801);      // 250000 uncapped
  EXPECT_FLOAT_EQ(g.width, 1e6f);   // w itself is the box's (the vector is divided by it)
  const HandGeometry normal = hand_geometry(p, kBox, kImage);
  EXPECT_EQ(normal.open_radius, 2);  // a real box is not touched: round(0.025 x 80)
  EXPECT_EQ(normal.hand_side, 20);
  HandDetector d(p, any_classifier());
  cv::Mat frame(kImage, CV_8UC3, cv::Scalar(0, 0, 0));  // all skin for this classifier
  EXPECT_EQ(d.detect(frame, {0, 0, 1e6f, 1e6f}).kind, HandKind::None);
  EXPECT_EQ(d.last_mask().size(), cv::Size(400, 400));
}

TEST(HandDetector, WholeStageRemovesFaceAndLegsAndFindsTheArm) {
  // GIVEN the committed model, a blue frame and a skin-coloured person drawn into the box (100,100,80,160).
  HandsParams p;
  const SkinModel model = SkinModel::load(resolve_project_path(p.skin.model));
  HandDetector d(p, SkinClassifier(model, p.skin.threshold));
  const cv::Scalar skin(90, 120, 170), blue(200, 60, 20);  // B, G, R
  ASSERT_GT(model.level(90, 120, 170), 200);
  ASSERT_LT(model.level(200, 60, 20), 10);
  cv::Mat frame(kImage, CV_8UC3, blue);
  cv::rectangle(frame, cv::Rect(125, 100, 30, 32), skin, cv::FILLED);  // face/neck: rows 100..131, removed
  cv::rectangle(frame, cv::Rect(110, 204, 60, 56), skin, cv::FILLED);  // legs: rows 204..259, removed
  cv::rectangle(frame, cv::Rect(102, 160, 10, 12), skin, cv::FILLED);  // resting hands at the box sides
  cv::rectangle(frame, cv::Rect(168, 160, 10, 12), skin, cv::FILLED);
  // WHEN nothing is stretched out THEN NONE (the resting hands are 28 and 29 px from p_bc.x, outside w/5 = 16).
  auto r = d.detect(frame, kBox);
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.skin_outside, 0);
  EXPECT_EQ(r.skin_inside, 240);
  // WHEN the right hand (12x12 at 30..41, 125..136) is stretched out to the image's left THEN OUT, x < 0.
  // λ1 F pulls the argmax in from the edge: (32, 127) has the whole hand in its square (F = 144):
  // 108 + 0.2 * 5 + 72 = 181, against (30, 125): 110 + 1.4 + 50 and (32, 128): 108 + 0.8 + 72.
  cv::rectangle(frame, cv::Rect(30, 125, 12, 12), skin, cv::FILLED);
  r = d.detect(frame, kBox);
  ASSERT_EQ(r.kind, HandKind::Out);
  EXPECT_EQ(r.hand, cv::Point(32, 127));
  EXPECT_EQ(r.hand_skin, 144);
  EXPECT_FLOAT_EQ(r.vector.x, -108);
  EXPECT_FLOAT_EQ(r.vector.y, -5);
  EXPECT_EQ(d.last_roi(), cv::Rect(4, 60, 272, 200));
}
