// check_message: the reasons a structurally bad message is rejected before any stage sees it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "message_checks.hpp"

namespace gpilot {
namespace {

image_t bgr(int w, int h) {
  image_t m{};
  m.width = w;
  m.height = h;
  m.row_stride = w * 3;
  m.pixel_format = image_t::PIXEL_FORMAT_BGR8;
  m.data.assign(static_cast<size_t>(w) * h * 3, 0);
  m.size = static_cast<int32_t>(m.data.size());
  return m;
}

TEST(MessageChecks, ImageSizesMustAgree) {
  EXPECT_EQ(check_message(bgr(4, 3)), "");
  image_t short_data = bgr(4, 3);
  short_data.data.resize(35);
  short_data.size = 35;
  EXPECT_EQ(check_message(short_data), "image data has 35 bytes, 4x3 needs 36");
  image_t lying_size = bgr(4, 3);
  lying_size.size = 40;
  EXPECT_EQ(check_message(lying_size), "image size field disagrees with its data");
  image_t bad_stride = bgr(4, 3);
  bad_stride.row_stride = 11;
  EXPECT_EQ(check_message(bad_stride), "row stride 11 is less than width x 3 bytes");
  image_t empty = bgr(4, 3);
  empty.width = 0;
  EXPECT_EQ(check_message(empty), "image has no pixels (0x3)");
  image_t fmt = bgr(4, 3);
  fmt.pixel_format = 9;
  EXPECT_EQ(check_message(fmt), "unknown pixel format 9");
}

TEST(MessageChecks, NanAndUnknownEnumsAreRejected) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  gesture_cmd_t g{};
  EXPECT_EQ(check_message(g), "");
  g.direction[1] = nan;
  EXPECT_EQ(check_message(g), "direction is not finite");
  g.direction[1] = 0;
  g.mode = 6;
  EXPECT_EQ(check_message(g), "mode 6 is not a known value");

  vehicle_state_t v{};
  v.source = vehicle_state_t::SOURCE_SIMULATOR;
  EXPECT_EQ(check_message(v), "");
  v.position[2] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(check_message(v), "position is not finite");

  hand_obs_t h{};
  h.user_box[2] = -1;
  EXPECT_EQ(check_message(h), "user_box has a negative size");
  h.user_box[2] = 0;
  h.skin_changed = 0.25f;
  EXPECT_EQ(check_message(h), "");
  h.skin_changed = NAN;
  EXPECT_EQ(check_message(h), "skin_changed not in 0..1");
  h.skin_changed = 1.5f;
  EXPECT_EQ(check_message(h), "skin_changed not in 0..1");
  h.skin_changed = 0;
  h.skin_scene_samples = -1;
  EXPECT_EQ(check_message(h), "negative skin sample count");

  tracker_init_t t{};
  t.command = tracker_init_t::COMMAND_SET_BOX;
  EXPECT_EQ(check_message(t), "manual box has no area");
  t.command = tracker_init_t::COMMAND_RESET;
  EXPECT_EQ(check_message(t), "");

  health_t hl{};
  hl.cpu_s = 12.5;
  EXPECT_EQ(check_message(hl), "");
  hl.cpu_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check_message(hl), "cpu_s is not finite");
  hl.cpu_s = -1;
  EXPECT_EQ(check_message(hl), "cpu_s -1 is negative");
}

constexpr float kBody[4] = {100, 50, 200, 400};  // a body box in a 640x480 frame

// A valid USER_TRACK: tracking kBody.
user_track_t tracking_user() {
  user_track_t t{};
  t.status = user_track_t::STATUS_TRACKING;
  t.image_width = 640;
  t.image_height = 480;
  std::copy(kBody, kBody + 4, t.box);
  return t;
}

TEST(MessageChecks, UserTrackFacingIsOneOfItsConstants) {
  user_track_t t = tracking_user();
  for (int8_t f : {user_track_t::FACING_UNKNOWN, user_track_t::FACING_TOWARD, user_track_t::FACING_AWAY}) {
    t.facing = f;
    EXPECT_EQ(check_message(t), "") << int(f);
  }
  t.facing = 3;
  EXPECT_NE(check_message(t).find("facing"), std::string::npos) << check_message(t);
  t.facing = -1;
  EXPECT_NE(check_message(t).find("facing"), std::string::npos) << check_message(t);
}

TEST(MessageChecks, UserTrackFaceBoxIsAllZeroOrAFiniteBoxInsideTheImage) {
  user_track_t t = tracking_user();
  // GIVEN no face in this frame (all zero): fine
  EXPECT_EQ(check_message(t), "");
  // and a face inside the image, up to its edges: fine
  const float face[4] = {600, 400, 40, 80};
  std::copy(face, face + 4, t.face_box);
  EXPECT_EQ(check_message(t), "");
  t.face_box[0] = 0;
  EXPECT_EQ(check_message(t), "");

  // WHEN a value is NaN or infinite, a size negative or zero, or the box leaves the image: rejected
  t.face_box[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(check_message(t), "face_box is not finite");
  t.face_box[1] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(check_message(t), "face_box is not finite");
  std::copy(face, face + 4, t.face_box);
  t.face_box[2] = -40;
  EXPECT_EQ(check_message(t), "face_box has a negative size");
  t.face_box[2] = 40;
  t.face_box[3] = -1;
  EXPECT_EQ(check_message(t), "face_box has a negative size");
  t.face_box[3] = 0;
  EXPECT_EQ(check_message(t), "face_box is neither all zero nor a box with an area");
  t.face_box[3] = 80.5f;
  EXPECT_EQ(check_message(t), "face_box is outside the 640x480 image");
  t.face_box[3] = 80;
  t.face_box[0] = -1;
  EXPECT_EQ(check_message(t), "face_box is outside the 640x480 image");
  t.face_box[0] = 601;
  EXPECT_EQ(check_message(t), "face_box is outside the 640x480 image");
  t.image_width = 0;  // a box or a face with no image size to be inside
  t.face_box[0] = 0;
  EXPECT_EQ(check_message(t), "box without an image size");
  std::fill(t.box, t.box + 4, 0.0f);
  t.status = user_track_t::STATUS_SEARCHING;
  EXPECT_EQ(check_message(t), "face_box is outside the 0x480 image");
}

// The finite but absurd values, each rejected by its field before any stage sizes or divides by it.
TEST(MessageChecks, AbsurdBoxesAndWidthsAreRejectedPerField) {
  user_track_t t = tracking_user();
  EXPECT_EQ(check_message(t), "");
  // A body box passing the frame's edges close up (2.5 image heights, corner above the image): fine
  t.box[1] = -300, t.box[3] = 1200;
  EXPECT_EQ(check_message(t), "");
  // and the 7 face heights of a face filling a 41 px frame (the fuzzer's tracker published 189 px): fine
  t.image_height = 41;
  t.box[1] = -10, t.box[3] = 189;
  EXPECT_EQ(check_message(t), "");
  t.image_height = 480;
  // The box of 1e6 px sent ahead of a frame (hands stalled 5.4 s, +545 MB)
  t.box[2] = 1e6f, t.box[3] = 1e6f;
  EXPECT_EQ(check_message(t), "box width 1e+06 is beyond 640 px image (32 x)");
  t.box[2] = 200;
  EXPECT_EQ(check_message(t), "box height 1e+06 is beyond 480 px image (32 x)");
  // A box width of 1e-45 (a yaw of -0.16 rad/s was flown on it)
  std::copy(kBody, kBody + 4, t.box);
  t.box[2] = 1e-45f;
  EXPECT_EQ(check_message(t), "box width 1.4013e-45 is below a pixel");
  std::copy(kBody, kBody + 4, t.box);
  t.box[0] = 1e9f;
  EXPECT_EQ(check_message(t), "box x 1e+09 is far outside 640 px image");
  // While searching there is no box (the tracker sends zeros); any other box is held to the same rules
  // (decide copies its width into the command: the fuzzer's decide target found widths of 3.6e-40 and 2.5e17
  // passing through a searching HAND_OBS into a GESTURE_CMD the flight stage then rejected)
  t.status = user_track_t::STATUS_SEARCHING;
  EXPECT_EQ(check_message(t), "box x 1e+09 is far outside 640 px image");
  std::fill(t.box, t.box + 4, 0.0f);
  EXPECT_EQ(check_message(t), "");
  t.image_width = 16385;
  EXPECT_EQ(check_message(t), "image size 16385x480 is larger than 16384 pixels a side");

  // A command with user_box_width 3.4e38 (a sideways command flown at 0.15 m/s) or 1e-45
  gesture_cmd_t g{};
  g.mode = gesture_cmd_t::MODE_FINE;
  g.direction[0] = 0.5f;
  g.user_box_width = 120;
  EXPECT_EQ(check_message(g), "");
  g.user_box_width = 3.4e38f;
  EXPECT_EQ(check_message(g), "user_box_width 3.4e+38 is beyond any image");
  g.user_box_width = 1e-45f;
  EXPECT_EQ(check_message(g), "user_box_width 1.4013e-45 is below a pixel");
  g.user_box_width = 0;  // no box (HOVER while searching)
  EXPECT_EQ(check_message(g), "");

  // A hand observation carries the track's box: the same rules while the track is not searching
  hand_obs_t h{};
  h.track_status = user_track_t::STATUS_TRACKING;
  h.image_width = 640;
  h.image_height = 480;
  std::copy(kBody, kBody + 4, h.user_box);
  EXPECT_EQ(check_message(h), "");
  h.user_box[2] = 1e-45f;
  EXPECT_EQ(check_message(h), "user_box width 1.4013e-45 is below a pixel");
  h.track_status = user_track_t::STATUS_SEARCHING;
  h.user_box[2] = 3.67699e-40f;
  EXPECT_EQ(check_message(h), "user_box width 3.67699e-40 is below a pixel");
  h.user_box[2] = 120;
  h.image_width = 0;  // hands publishes the track's box with its frame's size: the fuzzer found one without
  EXPECT_EQ(check_message(h), "user_box without an image size");

  // A manual box: at least a pixel, at most 32 of the largest image
  tracker_init_t i{};
  i.command = tracker_init_t::COMMAND_SET_BOX;
  std::copy(kBody, kBody + 4, i.box);
  EXPECT_EQ(check_message(i), "");
  i.box[3] = 1e-45f;
  EXPECT_EQ(check_message(i), "box height 1.4013e-45 is below a pixel");
  i.box[3] = 1e6f;
  EXPECT_EQ(check_message(i), "box height 1e+06 is beyond any image (32 x)");
}

}  // namespace
}  // namespace gpilot
