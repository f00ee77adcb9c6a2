// The One Euro filter and the landmark smoothing against values worked out by hand from MediaPipe's
// OneEuroFilter (alpha = 1 / (1 + rate / (2 pi cutoff))).
#include <gtest/gtest.h>

#include "pose/landmark_smoothing.hpp"
#include "pose/one_euro_filter.hpp"

namespace gpilot {
namespace {

constexpr int64_t kTenthSecond = 100000;  // microseconds

TEST(OneEuroFilter, BetaZeroIsALowPassAtTheMinCutoffAtTheMeasuredRate) {
  OneEuroFilter f(OneEuroParams{1.0, 0.0, 1.0}, 30.0);
  // GIVEN 0 then 1 a tenth of a second later (10 Hz)
  EXPECT_DOUBLE_EQ(f.apply(0.0, 1000000, 1.0), 0.0);  // the first value passes
  // THEN alpha(1 Hz at 10 Hz) = 0.38587
  EXPECT_NEAR(f.apply(1.0, 1000000 + kTenthSecond, 1.0), 0.3858695, 1e-6);
}

TEST(OneEuroFilter, SpeedRaisesTheCutoffScaledByTheValueScale) {
  // GIVEN beta 1: a step of 1 in 0.1 s is a speed of 10, low-passed to 3.8587, cutoff 4.8587 Hz
  OneEuroFilter f(OneEuroParams{1.0, 1.0, 1.0}, 30.0);
  f.apply(0.0, 0, 1.0);
  EXPECT_NEAR(f.apply(1.0, kTenthSecond, 1.0), 0.7532575, 1e-6);
  // and holding 1: the speed decays, the value closes in
  EXPECT_NEAR(f.apply(1.0, 2 * kTenthSecond, 1.0), 0.9208467, 1e-6);
  // value scale 0.5 halves the speed (an object twice as large moving the same pixels)
  OneEuroFilter g(OneEuroParams{1.0, 1.0, 1.0}, 30.0);
  g.apply(0.0, 0, 0.5);
  EXPECT_NEAR(g.apply(1.0, kTenthSecond, 0.5), 0.6479572, 1e-6);
}

TEST(OneEuroFilter, TimeNotAdvancingPassesTheValueAndResetForgets) {
  OneEuroFilter f(OneEuroParams{1.0, 0.0, 1.0}, 30.0);
  f.apply(0.0, 500, 1.0);
  EXPECT_DOUBLE_EQ(f.apply(7.0, 500, 1.0), 7.0);  // same utime: unfiltered, state unchanged
  EXPECT_NEAR(f.apply(1.0, 500 + 50000, 1.0), 0.2390572, 1e-6);  // 20 Hz from the first value 0
  f.reset();
  EXPECT_DOUBLE_EQ(f.apply(5.0, 0, 1.0), 5.0);
}

TEST(LandmarkSmoothing, StaticPoseStaysAndAJumpIsFollowedPartly) {
  PoseSmoothingParams p;
  LandmarkSmoothing s(p);
  PoseLandmarks l{};
  for (int i = 0; i < kPoseLandmarkCount; ++i) l[static_cast<size_t>(i)] = {100.0f + i, 50.0f + 4 * i, 0.0f, 1.0f, 1.0f};
  std::array<cv::Point2f, 2> aux{cv::Point2f(110, 150), cv::Point2f(110, 40)};
  // GIVEN the same pose twice: unchanged
  PoseLandmarks a = l;
  auto aux_a = aux;
  s.apply(a, aux_a, 0);
  a = l, aux_a = aux;
  s.apply(a, aux_a, 33333);
  EXPECT_FLOAT_EQ(a[11].x, l[11].x);
  EXPECT_FLOAT_EQ(aux_a[1].y, 40.0f);
  // WHEN a wrist jumps 20 px and visibility drops to 0
  PoseLandmarks b = l;
  b[15].x += 20.0f;
  b[15].visibility = 0.0f;
  auto aux_b = aux;
  s.apply(b, aux_b, 66666);
  // THEN the wrist moves part of the way and visibility by MediaPipe's 0.1
  EXPECT_GT(b[15].x, l[15].x + 1.0f);
  EXPECT_LT(b[15].x, l[15].x + 20.0f);
  EXPECT_NEAR(b[15].visibility, 0.9f, 1e-6);
  // disabled: untouched
  p.enabled = false;
  LandmarkSmoothing off(p);
  PoseLandmarks c = b;
  off.apply(c, aux_b, 0);
  EXPECT_FLOAT_EQ(c[15].x, b[15].x);
}

}  // namespace
}  // namespace gpilot
