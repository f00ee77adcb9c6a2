// GestureDecider: one command per observation, normalisation by box width, stale history emptied.
#include <gtest/gtest.h>

#include "gesture_decider.hpp"

namespace gpilot {
namespace {

constexpr int64_t kT0 = 1700000000000000;
constexpr int64_t kFrameUs = 40000;  // 25 fps

// These tests are about Alg. 3 and the history rules: the paper's rule, whatever the default is.
DecideParams paper() {
  DecideParams p;
  p.rule = "paper";
  return p;
}

HandObservation out_obs(int i, Vec2 v, double box_width = 200.0, int32_t track = 1) {
  HandObservation o;
  o.utime = kT0 + i * kFrameUs;
  o.seq = i;
  o.track_id = track;
  o.kind = HandObservation::Kind::Out;
  o.vector = v;
  o.user_box_width = box_width;
  return o;
}

TEST(GestureDecider, CommandCarriesFrameSeqUtimeAndNormalisedDirection) {
  GestureDecider d{paper()};
  GestureCommand c;
  for (int i = 0; i < 31; ++i) {
    c = d.update(out_obs(i, {-100, 20}));
    EXPECT_EQ(c.seq, i);
    EXPECT_EQ(c.utime, kT0 + i * kFrameUs);
    if (i < 30) {
      EXPECT_EQ(c.mode, GestureMode::Hover) << i;
    }
  }
  // 31 non-zero entries > 30: FINE, x/y divided by the box width
  EXPECT_EQ(c.mode, GestureMode::Fine);
  EXPECT_DOUBLE_EQ(c.direction[0], -0.5);
  EXPECT_DOUBLE_EQ(c.direction[1], 0.1);
  EXPECT_EQ(c.direction[2], 0.0);
  EXPECT_EQ(c.user_box_width, 200.0);
  EXPECT_EQ(c.n_out, 31);
  EXPECT_EQ(c.buffer_fill, 31);
}

TEST(GestureDecider, DirectionDoesNotChangeWithRange) {
  // The same arm seen at twice the distance: half the pixels, half the box.
  GestureDecider near_d{paper()}, far_d{paper()};
  GestureCommand near_c, far_c;
  for (int i = 0; i < 40; ++i) {
    near_c = near_d.update(out_obs(i, {-120, 30}, 240));
    far_c = far_d.update(out_obs(i, {-60, 15}, 120));
  }
  // a FINE command both times (zero directions would compare equal whatever the normalisation did)
  ASSERT_EQ(near_c.mode, GestureMode::Fine);
  ASSERT_EQ(far_c.mode, GestureMode::Fine);
  // in box widths: (-120, 30) / 240
  EXPECT_DOUBLE_EQ(near_c.direction[0], -0.5);
  EXPECT_DOUBLE_EQ(near_c.direction[1], 0.125);
  EXPECT_DOUBLE_EQ(near_c.direction[0], far_c.direction[0]);
  EXPECT_DOUBLE_EQ(near_c.direction[1], far_c.direction[1]);
}

TEST(GestureDecider, FrontObservationsComeCloser) {
  GestureDecider d{paper()};
  GestureCommand c;
  for (int i = 0; i < 31; ++i) {
    HandObservation o = out_obs(i, {3, -25});
    o.kind = HandObservation::Kind::Front;
    c = d.update(o);
  }
  EXPECT_EQ(c.mode, GestureMode::Closer);
  EXPECT_EQ(c.direction[0], 0.0);
  EXPECT_EQ(c.direction[2], 1.0);
  EXPECT_EQ(c.n_front_higher, 31);
}

TEST(GestureDecider, GapLongerThanTimeoutEmptiesBuffers) {
  GestureDecider d{paper()};  // gap timeout 0.5 s
  for (int i = 0; i < 40; ++i) d.update(out_obs(i, {-100, 0}));
  // GIVEN a FINE command, WHEN the next frame comes 0.6 s after the last
  HandObservation late = out_obs(39, {-100, 0});
  late.utime += 600000;
  const GestureCommand c = d.update(late);
  EXPECT_EQ(d.last_reset(), GestureDecider::Reset::Gap);
  EXPECT_EQ(c.mode, GestureMode::Hover);
  EXPECT_EQ(c.buffer_fill, 1);
}

TEST(GestureDecider, GapWithinTimeoutKeepsHistory) {
  GestureDecider d{paper()};
  for (int i = 0; i < 40; ++i) d.update(out_obs(i, {-100, 0}));
  HandObservation o = out_obs(39, {-100, 0});
  o.utime += 400000;
  EXPECT_EQ(d.update(o).mode, GestureMode::Fine);
  EXPECT_EQ(d.last_reset(), GestureDecider::Reset::None);
}

TEST(GestureDecider, NewUserEmptiesBuffers) {
  GestureDecider d{paper()};
  for (int i = 0; i < 40; ++i) d.update(out_obs(i, {-100, 0}, 200, 1));
  const GestureCommand c = d.update(out_obs(40, {-100, 0}, 200, 2));
  EXPECT_EQ(d.last_reset(), GestureDecider::Reset::NewUser);
  EXPECT_EQ(c.mode, GestureMode::Hover);
  EXPECT_EQ(c.track_id, 2);
}

TEST(GestureDecider, LostTrackEmptiesBuffersAndHovers) {
  GestureDecider d{paper()};
  for (int i = 0; i < 40; ++i) d.update(out_obs(i, {-100, 0}));
  HandObservation lost = out_obs(40, {-100, 0});
  lost.tracking = false;
  const GestureCommand c = d.update(lost);
  EXPECT_EQ(c.mode, GestureMode::Hover);
  EXPECT_EQ(c.buffer_fill, 0);
  // and the history does not come back with the track
  EXPECT_EQ(d.update(out_obs(41, {-100, 0})).mode, GestureMode::Hover);
}

TEST(GestureDecider, BoxWithoutWidthHovers) {
  GestureDecider d{paper()};
  GestureCommand c;
  for (int i = 0; i < 40; ++i) c = d.update(out_obs(i, {-100, 0}, 0.0));
  EXPECT_EQ(c.mode, GestureMode::Hover);
  EXPECT_EQ(c.direction[0], 0.0);
}

TEST(GestureDecider, TimeGoingBackwardsEmptiesBuffers) {
  GestureDecider d{paper()};
  for (int i = 0; i < 40; ++i) d.update(out_obs(i, {-100, 0}));
  d.update(out_obs(10, {-100, 0}));
  EXPECT_EQ(d.last_reset(), GestureDecider::Reset::TimeBackwards);
}

}  // namespace
}  // namespace gpilot
