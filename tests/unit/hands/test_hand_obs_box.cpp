// One body box from the tracker to decide: HAND_OBS's user box is USER_TRACK's, and its shoulder centre, body
// centre, hand square and vector are measured on that box, also on a frame with a face whose preset head-body
// ratios would make another box; decide normalises by that box's width. A user the tracker finds turned away
// gives no command.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "body_proportions.hpp"
#include "decide/decide_service.hpp"
#include "hands/hands_core_factory.hpp"
#include "hands/hands_service.hpp"
#include "image_codec.hpp"

using namespace gpilot;

namespace {

const cv::Scalar kSkin(90, 120, 170), kBlue(200, 60, 20);  // B, G, R: the committed table says 247 and ~0

TEST(HandObsBox, GivenAFaceWhoseFittedRatiosDifferFromThePresetWhenObservedThenAllIsOnTheTrackersBox) {
  // GIVEN a face 32 x 32 at (124, 108) and a track fitted to a narrower, shorter, off-centre body than the
  // preset (2.75 x 7 faces, centred): box 70.4 x 192 at (108, 100); the preset would make 88 x 224 at (96, 100)
  const cv::Rect2d face(124, 108, 32, 32);
  const BodyProportions fitted{2.2, 6.0, 0.25, 0.1};
  const cv::Rect2d box = body_from_face(face, fitted);
  ASSERT_NEAR(box.x, 108.0, 1e-9);
  ASSERT_NEAR(box.width, 70.4, 1e-9);
  ASSERT_NE(cv::Rect(body_from_face(face, BodyProportions{})), cv::Rect(box));
  // AND a bare arm stretched out to the image's right, its hand at x 230..247 (shoulder height)
  cv::Mat frame(400, 400, CV_8UC3, kBlue);
  cv::rectangle(frame, cv::Rect(face), kSkin, cv::FILLED);
  cv::rectangle(frame, cv::Rect(230, 130, 18, 18), kSkin, cv::FILLED);
  HandsParams p;
  p.method = "skin";
  p.arm_connected = false;  // no arm drawn: the box is what is tested here
  const auto method = make_hand_method(p);
  user_track_t track{};
  track.seq = 7;
  track.status = user_track_t::STATUS_TRACKING;
  track.track_id = 1;
  track.box[0] = static_cast<float>(box.x), track.box[1] = static_cast<float>(box.y);
  track.box[2] = static_cast<float>(box.width), track.box[3] = static_cast<float>(box.height);
  track.face_box[0] = 124, track.face_box[1] = 108, track.face_box[2] = 32, track.face_box[3] = 32;
  track.image_width = track.image_height = 400;
  const image_t image = mat_to_image(frame, 1000, 7);
  // WHEN the stage takes the pair
  hand_obs_t obs;
  ASSERT_EQ(hands_on_pair(*method, image, track, ImageLimits{}, obs), "");
  // THEN the box published is the tracker's
  for (int i = 0; i < 4; ++i) EXPECT_EQ(obs.user_box[i], track.box[i]);
  // AND p_uc, p_bc are that box's (centre x; 0.2 and 0.5 of its height down), not the preset box's (y 144.8, 212)
  const float cx = track.box[0] + track.box[2] / 2;
  EXPECT_FLOAT_EQ(obs.shoulder_centre[0], cx);
  EXPECT_FLOAT_EQ(obs.shoulder_centre[1], track.box[1] + 0.2f * track.box[3]);
  EXPECT_FLOAT_EQ(obs.body_centre[0], cx);
  EXPECT_FLOAT_EQ(obs.body_centre[1], track.box[1] + 0.5f * track.box[3]);
  // AND the hand is OUT, its square the box's (w/4 = 18 px, not the preset's 22) and the vector runs from p_uc
  // to the square's centre
  ASSERT_EQ(obs.kind, hand_obs_t::KIND_OUT);
  const int side = static_cast<int>(std::lround(track.box[2] * p.hand_square_ratio));
  EXPECT_EQ(obs.hand_box[2], side);
  EXPECT_EQ(obs.hand_box[3], side);
  EXPECT_NEAR(obs.vector[0], obs.hand_box[0] + side / 2 - obs.shoulder_centre[0], 1e-3);
  EXPECT_NEAR(obs.vector[1], obs.hand_box[1] + side / 2 - obs.shoulder_centre[1], 1e-3);
  EXPECT_GE(obs.hand_box[0] + side / 2, 230);
  // AND decide's speed is the vector over that box's width
  EXPECT_EQ(to_hand_observation(obs).user_box_width, track.box[2]);

  // AND the same pair from a user the tracker finds turned away (user_track_t.facing) gives no command: the
  // paper's user faces the drone
  track.facing = user_track_t::FACING_AWAY;
  ASSERT_EQ(hands_on_pair(*method, image, track, ImageLimits{}, obs), "");
  EXPECT_EQ(obs.kind, hand_obs_t::KIND_NONE);
  EXPECT_EQ(obs.vector[0], 0.0f);
  EXPECT_EQ(obs.vector[1], 0.0f);
  EXPECT_EQ(obs.hand_box[2], 0.0f);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(obs.user_box[i], track.box[i]);
  // AND facing it again, the arm is OUT again
  track.facing = user_track_t::FACING_TOWARD;
  ASSERT_EQ(hands_on_pair(*method, image, track, ImageLimits{}, obs), "");
  EXPECT_EQ(obs.kind, hand_obs_t::KIND_OUT);
}

}  // namespace
