// Every message type survives encode/decode with known field values, and a truncated encoding is refused.
#include <gtest/gtest.h>

#include <vector>

#include "message_checks.hpp"

namespace gpilot {
namespace {

template <class Msg>
Msg round_trip(const Msg& in, std::vector<uint8_t>* bytes_out = nullptr) {
  std::vector<uint8_t> bytes(in.getEncodedSize());
  EXPECT_EQ(in.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  Msg out{};  // value-initialised, as callers write it: catches LCM's float aliasing under -O2 (CMakeLists.txt)
  EXPECT_EQ(out.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  // A truncated copy must not decode.
  Msg cut;
  EXPECT_LT(cut.decode(bytes.data(), 0, static_cast<int>(bytes.size()) - 1), 0);
  if (bytes_out) *bytes_out = bytes;
  return out;
}

TEST(LcmTypes, ImageRoundTrip) {
  image_t m;
  m.utime = 1700000000123456;
  m.seq = 42;
  m.width = 3;
  m.height = 2;
  m.row_stride = 9;
  m.pixel_format = image_t::PIXEL_FORMAT_BGR8;
  m.data = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18};
  m.size = 18;
  const image_t r = round_trip(m);
  EXPECT_EQ(r.utime, 1700000000123456);
  EXPECT_EQ(r.seq, 42);
  EXPECT_EQ(r.width, 3);
  EXPECT_EQ(r.height, 2);
  EXPECT_EQ(r.row_stride, 9);
  EXPECT_EQ(r.pixel_format, image_t::PIXEL_FORMAT_BGR8);
  EXPECT_EQ(r.data, m.data);
  EXPECT_EQ(check_message(r), "");
}

TEST(LcmTypes, TrackerInitRoundTrip) {
  tracker_init_t m;
  m.utime = 5;
  m.seq = 6;
  m.command = tracker_init_t::COMMAND_SET_BOX;
  m.box[0] = 10.5f; m.box[1] = 20; m.box[2] = 30; m.box[3] = 40;
  m.source = "gpilot-view";
  const auto r = round_trip(m);
  EXPECT_EQ(r.command, tracker_init_t::COMMAND_SET_BOX);
  EXPECT_FLOAT_EQ(r.box[0], 10.5f);
  EXPECT_FLOAT_EQ(r.box[3], 40.0f);
  EXPECT_EQ(r.source, "gpilot-view");
}

TEST(LcmTypes, UserTrackRoundTrip) {
  user_track_t m{};
  m.utime = 7;
  m.seq = 8;
  m.status = user_track_t::STATUS_TRACKING;
  m.box[0] = 100; m.box[1] = 50; m.box[2] = 80; m.box[3] = 200;
  m.confidence = 12.5f;
  m.init_source = user_track_t::INIT_FACE;
  m.track_id = 3;
  m.image_width = 640;
  m.image_height = 480;
  const auto r = round_trip(m);
  EXPECT_EQ(r.status, user_track_t::STATUS_TRACKING);
  EXPECT_FLOAT_EQ(r.box[3], 200.0f);
  EXPECT_FLOAT_EQ(r.confidence, 12.5f);
  EXPECT_EQ(r.init_source, user_track_t::INIT_FACE);
  EXPECT_EQ(r.track_id, 3);
  EXPECT_EQ(r.image_width, 640);
}

TEST(LcmTypes, HandObsRoundTrip) {
  hand_obs_t m{};
  m.utime = 9;
  m.seq = 10;
  m.track_id = 2;
  m.track_status = user_track_t::STATUS_TRACKING;
  m.user_box[2] = 80;
  m.shoulder_centre[0] = 140; m.shoulder_centre[1] = 90;
  m.body_centre[0] = 140; m.body_centre[1] = 150;
  m.kind = hand_obs_t::KIND_OUT;
  m.vector[0] = -75.25f; m.vector[1] = -10;
  m.hand_box[2] = 20; m.hand_box[3] = 20;
  m.hand_skin = 250;
  m.skin_outside = 400;
  m.skin_inside = 12;
  const auto r = round_trip(m);
  EXPECT_EQ(r.kind, hand_obs_t::KIND_OUT);
  EXPECT_FLOAT_EQ(r.vector[0], -75.25f);
  EXPECT_FLOAT_EQ(r.shoulder_centre[1], 90.0f);
  EXPECT_EQ(r.hand_skin, 250);
  EXPECT_EQ(r.skin_outside, 400);
}

TEST(LcmTypes, GestureCmdRoundTrip) {
  gesture_cmd_t m{};
  m.utime = 11;
  m.seq = 12;
  m.mode = gesture_cmd_t::MODE_CLOSER;
  m.direction[2] = 1;
  m.user_box_width = 80;
  m.n_out = 3;
  m.n_front_higher = 31;
  m.n_front_lower = 0;
  m.buffer_fill = 60;
  const auto r = round_trip(m);
  EXPECT_EQ(r.mode, gesture_cmd_t::MODE_CLOSER);
  EXPECT_FLOAT_EQ(r.direction[2], 1.0f);
  EXPECT_EQ(r.n_front_higher, 31);
  EXPECT_EQ(r.buffer_fill, 60);
}

TEST(LcmTypes, FlightControlRoundTrip) {
  flight_control_t m{};
  m.utime = 13;
  m.seq = 14;
  m.command = flight_control_t::COMMAND_TAKEOFF;
  m.takeoff_altitude = 2.5f;
  m.source = "gpilot-ctl";
  const auto r = round_trip(m);
  EXPECT_EQ(r.command, flight_control_t::COMMAND_TAKEOFF);
  EXPECT_FLOAT_EQ(r.takeoff_altitude, 2.5f);
  EXPECT_EQ(r.source, "gpilot-ctl");
}

TEST(LcmTypes, FlightSetpointRoundTrip) {
  flight_setpoint_t m{};
  m.utime = 15;
  m.seq = -1;
  m.velocity[0] = 0.5f; m.velocity[1] = -0.25f; m.velocity[2] = 0.125f;
  m.yaw_rate = -0.3f;
  m.engaged = true;
  m.mode = gesture_cmd_t::MODE_FINE;
  m.reasons = flight_setpoint_t::REASON_CLIPPED | flight_setpoint_t::REASON_COMMAND_DELAY;
  const auto r = round_trip(m);
  EXPECT_EQ(r.seq, -1);
  EXPECT_FLOAT_EQ(r.velocity[1], -0.25f);
  EXPECT_FLOAT_EQ(r.yaw_rate, -0.3f);
  EXPECT_TRUE(r.engaged);
  EXPECT_EQ(r.reasons, 256 | 128);
}

TEST(LcmTypes, VehicleStateRoundTrip) {
  vehicle_state_t m{};
  m.utime = 17;
  m.seq = 18;
  m.position[2] = -1.5f;
  m.velocity[0] = 0.1f;
  m.attitude[2] = 1.25f;
  m.yaw_rate = 0.5f;
  m.armed = true;
  m.source = vehicle_state_t::SOURCE_MAVLINK;
  m.landed_state = vehicle_state_t::LANDED_IN_AIR;
  const auto r = round_trip(m);
  EXPECT_FLOAT_EQ(r.position[2], -1.5f);
  EXPECT_FLOAT_EQ(r.attitude[2], 1.25f);
  EXPECT_TRUE(r.armed);
  EXPECT_EQ(r.source, vehicle_state_t::SOURCE_MAVLINK);
  EXPECT_EQ(r.landed_state, vehicle_state_t::LANDED_IN_AIR);
}

TEST(LcmTypes, GroundTruthRoundTrip) {
  ground_truth_t m{};
  m.utime = 19;
  m.seq = 20;
  m.user_box[0] = 270; m.user_box[2] = 100;
  m.left_hand[0] = 420; m.left_hand[1] = 180;
  m.gesture = ground_truth_t::GESTURE_OUT;
  m.expected_kind = hand_obs_t::KIND_OUT;
  m.expected_vector[0] = 100;
  m.expected_mode = gesture_cmd_t::MODE_FINE;
  m.expected_direction[0] = 1;
  m.person_position[0] = 3;
  m.camera_yaw = 0.1f;
  const auto r = round_trip(m);
  EXPECT_FLOAT_EQ(r.user_box[0], 270.0f);
  EXPECT_FLOAT_EQ(r.left_hand[0], 420.0f);
  EXPECT_EQ(r.gesture, ground_truth_t::GESTURE_OUT);
  EXPECT_EQ(r.expected_mode, gesture_cmd_t::MODE_FINE);
  EXPECT_FLOAT_EQ(r.person_position[0], 3.0f);
  EXPECT_FLOAT_EQ(r.camera_yaw, 0.1f);
}

TEST(LcmTypes, HealthRoundTrip) {
  health_t m{};
  m.utime = 21;
  m.seq = 22;
  m.name = "gpilot-hands";
  m.pid = 1234;
  m.state = health_t::STATE_DEGRADED;
  m.state_detail = "no USER_TRACK";
  m.messages_in = 100;
  m.messages_out = 99;
  m.rejected = 1;
  m.dropped = 2;
  m.last_reject_reason = "CAMERA: image has no pixels";
  m.rate_in_hz = 30;
  m.processing_ms_p50 = 0.25f;
  m.processing_ms_p99 = 0.75f;
  const auto r = round_trip(m);
  EXPECT_EQ(r.name, "gpilot-hands");
  EXPECT_EQ(r.pid, 1234);
  EXPECT_EQ(r.state, health_t::STATE_DEGRADED);
  EXPECT_EQ(r.messages_out, 99);
  EXPECT_EQ(r.last_reject_reason, "CAMERA: image has no pixels");
  EXPECT_FLOAT_EQ(r.processing_ms_p99, 0.75f);
}

}  // namespace
}  // namespace gpilot
