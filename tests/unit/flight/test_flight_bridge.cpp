// FlightBridge: frames and signs, scaling, yaw, the 600 ms spacing, and every safety rule with its reason bit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "flight_bridge.hpp"

namespace gpilot {
namespace {

constexpr int64_t kT0 = 1700000000000000;
constexpr int64_t kMs = 1000;

GestureCommand fine(double x, double y, int64_t seq = 1) {
  GestureCommand c;
  c.seq = seq;
  c.track_id = 7;
  c.mode = GestureMode::Fine;
  c.direction[0] = x;
  c.direction[1] = y;
  c.user_box_width = 200;
  return c;
}

GestureCommand with_mode(GestureMode m, double z, int64_t seq = 1) {
  GestureCommand c = fine(0, 0, seq);
  c.mode = m;
  c.direction[2] = z;
  return c;
}

UserTrack centred_track() {
  UserTrack t;
  t.tracking = true;
  t.box[0] = 270;
  t.box[1] = 100;
  t.box[2] = 100;
  t.box[3] = 250;
  t.track_id = 7;
  t.image_width = 640;
  t.image_height = 480;
  return t;
}

// All inputs fresh at kT0, engaged.
BridgeInputs ready(const GestureCommand& c) {
  BridgeInputs in;
  in.now = kT0;
  in.command = c;
  in.command_received = kT0;
  in.track = centred_track();
  in.track_received = kT0;
  in.vehicle = VehicleState{};
  in.vehicle->position[2] = -1.5;  // 1.5 m up, inside the height band
  in.vehicle_received = kT0;
  in.engaged = true;
  return in;
}

// One update of a fresh bridge with params p, command c and the user box at y, h tall (the rest as ready's).
Setpoint with_box(const FlightParams& p, const GestureCommand& c, double box_y, double box_h) {
  FlightBridge b{p};
  BridgeInputs in = ready(c);
  in.track->box[1] = box_y;
  in.track->box[3] = box_h;
  return b.update(in);
}

TEST(FlightBridge, PointingToTheImageLeftFliesBodyLeft) {
  // Hand on the image's left (x < 0) = the user's right; camera -x = body -y (left of the drone).
  FlightBridge b{FlightParams{}};
  const Setpoint sp = b.update(ready(fine(-0.5, 0.0)));
  EXPECT_EQ(sp.reasons, 0);
  EXPECT_DOUBLE_EQ(sp.velocity[0], 0.0);
  EXPECT_DOUBLE_EQ(sp.velocity[1], -0.5);  // gain 1 m/s per box width
  EXPECT_DOUBLE_EQ(sp.velocity[2], 0.0);
  EXPECT_EQ(sp.mode, static_cast<int8_t>(GestureMode::Fine));
  EXPECT_TRUE(sp.engaged);
}

TEST(FlightBridge, ArmUpClimbsCloserGoesForwardFurtherBack) {
  FlightParams p;
  {
    FlightBridge b{p};
    GestureCommand up = fine(0.0, -0.4);
    up.mode = GestureMode::Up;
    const Setpoint sp = b.update(ready(up));
    EXPECT_DOUBLE_EQ(sp.velocity[2], -0.4);  // body z is down: negative = climb
    EXPECT_EQ(sp.reasons, 0);
  }
  {
    FlightBridge b{p};
    const Setpoint sp = b.update(ready(with_mode(GestureMode::Closer, 1.0)));
    EXPECT_DOUBLE_EQ(sp.velocity[0], 0.5);  // forward, toward the user, at speed_along_axis
  }
  {
    FlightBridge b{p};
    const Setpoint sp = b.update(ready(with_mode(GestureMode::Further, -1.0)));
    EXPECT_DOUBLE_EQ(sp.velocity[0], -0.5);
  }
}

TEST(FlightBridge, NoClimbAboveTheHeightBandNoDescentBelowIt) {
  FlightParams p;
  p.min_height_m = 0.5;
  p.max_height_m = 3.0;
  GestureCommand up = fine(0.0, -0.4), down = fine(0.0, 0.4);
  up.mode = GestureMode::Up;
  down.mode = GestureMode::Down;
  struct Case { GestureCommand c; double height, vz; int32_t reasons; };
  for (const Case& k : {Case{up, 2.9, -0.4, 0}, Case{up, 3.0, 0.0, reason::kHeightLimit},
                        Case{down, 3.0, 0.4, 0}, Case{down, 0.6, 0.4, 0}, Case{down, 0.5, 0.0, reason::kHeightLimit},
                        Case{up, 0.2, -0.4, 0}}) {
    FlightBridge b{p};
    BridgeInputs in = ready(k.c);
    in.vehicle->position[2] = -k.height;
    const Setpoint sp = b.update(in);
    EXPECT_DOUBLE_EQ(sp.velocity[2], k.vz) << "at " << k.height << " m";
    EXPECT_EQ(sp.reasons, k.reasons) << "at " << k.height << " m";
  }
}

TEST(FlightBridge, MotionsThatTakeTheFaceOutOfViewAreHeld) {
  FlightParams p;
  p.view_box_ratio = 0;  // a face at the bottom has the box below the image: only the face band here
  GestureCommand down = fine(0.0, 0.4), up = fine(0.0, -0.4), side_down = fine(-0.5, 0.4);
  down.mode = GestureMode::Down;
  up.mode = GestureMode::Up;
  const GestureCommand closer = with_mode(GestureMode::Closer, 1.0), further = with_mode(GestureMode::Further, -1.0);
  struct Case { const char* what; GestureCommand c; double box_y; double vx, vy, vz; bool held; };
  // Box height 250: the face band is its top 37.5 px.
  for (const Case& k : {Case{"descend, face in view", down, 10, 0, 0, 0.4, false},
                        Case{"descend, face at the top", down, 0, 0, 0, 0.0, true},
                        Case{"closer, face at the top", closer, -5, 0, 0, 0.0, true},
                        Case{"further, face at the top", further, -5, -0.5, 0, 0.0, false},
                        Case{"climb, face at the top", up, -5, 0, 0, -0.4, false},
                        Case{"sideways and down, face at the top", side_down, -5, 0, -0.5, 0.0, true},
                        Case{"climb, face at the bottom", up, 480 - 37.5, 0, 0, 0.0, true},
                        Case{"climb, face just above the bottom", up, 480 - 38.5, 0, 0, -0.4, false}}) {
    FlightBridge b{p};
    BridgeInputs in = ready(k.c);
    in.track->box[1] = k.box_y;
    const Setpoint sp = b.update(in);
    EXPECT_DOUBLE_EQ(sp.velocity[0], k.vx) << k.what;
    EXPECT_DOUBLE_EQ(sp.velocity[1], k.vy) << k.what;
    EXPECT_DOUBLE_EQ(sp.velocity[2], k.vz) << k.what;
    EXPECT_EQ((sp.reasons & reason::kViewLimit) != 0, k.held) << k.what;
  }
  p.keep_face_in_view = false;
  FlightBridge b{p};
  BridgeInputs in = ready(down);
  in.track->box[1] = -20;
  EXPECT_DOUBLE_EQ(b.update(in).velocity[2], 0.4) << "keep_face_in_view off";
}

TEST(FlightBridge, NoClosingInOnceTheUserFillsTheImage) {
  FlightParams p;  // closest_box_height_ratio 0.65: a box of 312 px in a 480 px image
  const GestureCommand closer = with_mode(GestureMode::Closer, 1.0), further = with_mode(GestureMode::Further, -1.0);
  struct Case { const char* what; GestureCommand c; double box_h; double vx; bool held; };
  for (const Case& k : {Case{"closer, box 311 px", closer, 311, 0.5, false},
                        Case{"closer, box 312 px", closer, 312, 0.0, true},
                        Case{"closer, box beyond the image", closer, 900, 0.0, true},
                        Case{"further, box 600 px", further, 600, -0.5, false}}) {
    const Setpoint sp = with_box(p, k.c, 20, k.box_h);  // face band well inside: only the range limit can hold it
    EXPECT_DOUBLE_EQ(sp.velocity[0], k.vx) << k.what;
    EXPECT_EQ((sp.reasons & reason::kRangeLimit) != 0, k.held) << k.what;
    EXPECT_EQ(sp.reasons & reason::kViewLimit, 0) << k.what;
  }
  p.closest_box_height_ratio = 0;
  p.view_box_ratio = 0;  // a 900 px box reaches below the image too
  EXPECT_DOUBLE_EQ(with_box(p, closer, 100, 900).velocity[0], 0.5) << "closest_box_height_ratio 0: no limit";
}

TEST(FlightBridge, NoClimbingNorClosingInOnceTheUserBoxReachesTheImagesBottom) {
  FlightParams p;  // view_box_ratio 1 (the box's bottom); a 480 px image; 250 px boxes, the face band inside and
                   // below the 312 px range limit
  GestureCommand up = fine(0.0, -0.4), down = fine(0.0, 0.4), up_left = fine(-0.5, -0.4);
  up.mode = GestureMode::Up;
  down.mode = GestureMode::Down;
  const GestureCommand closer = with_mode(GestureMode::Closer, 1.0), further = with_mode(GestureMode::Further, -1.0);
  struct Case { const char* what; GestureCommand c; double box_y; double vx, vy, vz; int32_t held; };
  const int32_t view = reason::kViewLimit, range = reason::kRangeLimit;
  for (const Case& k : {Case{"climb, box bottom at 479 px", up, 229, 0, 0, -0.4, 0},
                        Case{"climb, box bottom at 480 px", up, 230, 0, 0, 0.0, view},
                        Case{"climb, box below the image", up, 380, 0, 0, 0.0, view},
                        Case{"descend, box below the image", down, 380, 0, 0, 0.4, 0},
                        Case{"sideways and up, box below the image", up_left, 380, 0, -0.5, 0.0, view},
                        Case{"closer, box bottom at 479 px", closer, 229, 0.5, 0, 0, 0},
                        Case{"closer, box bottom at 480 px", closer, 230, 0.0, 0, 0, range},
                        Case{"further, box below the image", further, 380, -0.5, 0, 0, 0}}) {
    const Setpoint sp = with_box(p, k.c, k.box_y, 250);  // 230 + 250 = 480
    EXPECT_DOUBLE_EQ(sp.velocity[0], k.vx) << k.what;
    EXPECT_DOUBLE_EQ(sp.velocity[1], k.vy) << k.what;
    EXPECT_DOUBLE_EQ(sp.velocity[2], k.vz) << k.what;
    EXPECT_EQ(sp.reasons & (view | range), k.held) << k.what;
  }
  p.view_box_ratio = 0;
  EXPECT_DOUBLE_EQ(with_box(p, up, 380, 250).velocity[2], -0.4) << "view_box_ratio 0: no limit";
  EXPECT_DOUBLE_EQ(with_box(p, closer, 380, 250).velocity[0], 0.5) << "view_box_ratio 0: no limit";
}

TEST(FlightBridge, SpeedIsClippedToTheLimitsAndSaysSo) {
  FlightBridge b{FlightParams{}};  // max horizontal 1 m/s
  const Setpoint sp = b.update(ready(fine(-2.0, 0.0)));
  EXPECT_DOUBLE_EQ(sp.velocity[1], -1.0);
  EXPECT_EQ(sp.reasons, reason::kClipped);
  FlightBridge b2{FlightParams{}};  // max vertical 0.5 m/s
  GestureCommand down = fine(0.0, 0.9);
  down.mode = GestureMode::Down;
  const Setpoint sp2 = b2.update(ready(down));
  EXPECT_DOUBLE_EQ(sp2.velocity[2], 0.5);
  EXPECT_EQ(sp2.reasons, reason::kClipped);
}

TEST(FlightBridge, YawTurnsTowardTheUserWithDeadBandAndLimit) {
  FlightParams p;  // gain 2 rad/s per image width, dead band 0.05, limit 0.8
  FlightBridge b{p};
  BridgeInputs in = ready(GestureCommand{});
  in.command->track_id = 7;
  // user box centre at 0.6 of the width: offset +0.1 -> turn right at 0.2 rad/s
  in.track->box[0] = 0.6 * 640 - 50;
  EXPECT_NEAR(b.update(in).yaw_rate, 0.2, 1e-9);
  in.track->box[0] = 0.54 * 640 - 50;  // offset 0.04: inside the dead band
  EXPECT_EQ(b.update(in).yaw_rate, 0.0);
  in.track->box[0] = 0.0 - 50 + 10;  // far left: -0.48 * 2 = -0.96 -> limited to -0.8
  const Setpoint sp = b.update(in);
  EXPECT_DOUBLE_EQ(sp.yaw_rate, -0.8);
  EXPECT_EQ(sp.reasons, reason::kClipped);
}

TEST(FlightBridge, NotEngagedSendsZero) {
  FlightBridge b{FlightParams{}};
  BridgeInputs in = ready(fine(-0.5, 0.0));
  in.engaged = false;
  in.track->box[0] = 500;  // the user off centre: not even yaw moves
  const Setpoint sp = b.update(in);
  EXPECT_TRUE(sp.is_zero());
  EXPECT_EQ(sp.reasons, reason::kNotEngaged);
  EXPECT_FALSE(sp.engaged);
}

TEST(FlightBridge, StartupWithoutInputsSendsZero) {
  FlightBridge b{FlightParams{}};
  BridgeInputs in;
  in.now = kT0;
  in.engaged = true;
  Setpoint sp = b.update(in);
  EXPECT_TRUE(sp.is_zero());
  EXPECT_EQ(sp.reasons, reason::kStartup);
  EXPECT_EQ(sp.seq, -1);
  // a command and a track, but no vehicle state yet: still start-up
  in = ready(fine(-0.5, 0));
  in.vehicle.reset();
  sp = b.update(in);
  EXPECT_TRUE(sp.is_zero());
  EXPECT_EQ(sp.reasons, reason::kStartup);
}

TEST(FlightBridge, StaleCommandTrackOrVehicleSendsZero) {
  struct Case {
    int64_t BridgeInputs::*received;
    int32_t bit;
  };
  for (const Case c : {Case{&BridgeInputs::command_received, reason::kStaleCommand},
                       Case{&BridgeInputs::track_received, reason::kStaleTrack},
                       Case{&BridgeInputs::vehicle_received, reason::kStaleVehicle}}) {
    FlightBridge b{FlightParams{}};  // stale after 0.25 s
    BridgeInputs in = ready(fine(-0.5, 0));
    in.now = kT0 + 250 * kMs;  // exactly 0.25 s: still fresh
    in.command_received = in.track_received = in.vehicle_received = kT0 + 250 * kMs;
    in.*c.received = kT0;
    Setpoint sp = b.update(in);
    EXPECT_FALSE(sp.is_zero());
    EXPECT_EQ(sp.reasons, 0);
    in.now += 1;  // 0.250001 s old
    sp = b.update(in);
    EXPECT_TRUE(sp.is_zero());
    EXPECT_EQ(sp.reasons, c.bit);
  }
}

TEST(FlightBridge, LostOrSearchingTrackSendsZero) {
  FlightBridge b{FlightParams{}};
  BridgeInputs in = ready(fine(-0.5, 0));
  in.track->tracking = false;
  const Setpoint sp = b.update(in);
  EXPECT_TRUE(sp.is_zero());
  EXPECT_EQ(sp.reasons, reason::kTrackLost);
}

TEST(FlightBridge, CommandForAnotherUserSendsZero) {
  FlightBridge b{FlightParams{}};
  BridgeInputs in = ready(fine(-0.5, 0));
  in.track->track_id = 8;
  EXPECT_EQ(b.update(in).reasons, reason::kTrackLost);
}

TEST(FlightBridge, NaNOrOutOfRangeInputSendsZero) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<BridgeInputs> bad;
  bad.push_back(ready(fine(nan, 0)));
  bad.push_back(ready(fine(-3.5, 0)));  // beyond max_command_magnitude (3 box widths)
  bad.push_back(ready(with_mode(GestureMode::Closer, -1.0)));  // CLOSER must be z = +1
  bad.push_back(ready(with_mode(static_cast<GestureMode>(9), 0.0)));
  {
    GestureCommand c = fine(0.3, 0.0);
    c.mode = GestureMode::Hover;  // HOVER with a vector
    bad.push_back(ready(c));
  }
  {
    BridgeInputs in = ready(fine(-0.5, 0));
    in.track->box[2] = nan;
    bad.push_back(in);
  }
  {
    BridgeInputs in = ready(fine(-0.5, 0));
    in.track->image_width = 0;
    bad.push_back(in);
  }
  {
    BridgeInputs in = ready(fine(-0.5, 0));
    in.vehicle->position[2] = std::numeric_limits<double>::infinity();
    bad.push_back(in);
  }
  for (size_t i = 0; i < bad.size(); ++i) {
    FlightBridge b{FlightParams{}};
    const Setpoint sp = b.update(bad[i]);
    EXPECT_TRUE(sp.is_zero()) << i;
    EXPECT_EQ(sp.reasons, reason::kInvalidInput) << i;
    EXPECT_FALSE(b.last_invalid().empty()) << i;
  }
}

TEST(FlightBridge, LandingSendsZero) {
  FlightBridge b{FlightParams{}};
  BridgeInputs in = ready(fine(-0.5, 0));
  in.engaged = false;
  in.landing = true;
  EXPECT_EQ(b.update(in).reasons, reason::kLanding | reason::kNotEngaged);
}

TEST(FlightBridge, NewCommandsAreSpacedBy600Ms) {
  FlightParams paper;
  paper.command_spacing_s = 0.6;  // the paper's (the default is 0.3: decide README)
  FlightBridge b{paper};
  BridgeInputs in = ready(fine(-0.5, 0, 1));
  EXPECT_DOUBLE_EQ(b.update(in).velocity[1], -0.5);  // first command: taken at once
  // 100 ms later a different command: the previous one is held
  in.now = in.command_received = in.track_received = in.vehicle_received = kT0 + 100 * kMs;
  in.command = fine(0.5, 0, 2);
  Setpoint sp = b.update(in);
  EXPECT_DOUBLE_EQ(sp.velocity[1], -0.5);
  EXPECT_EQ(sp.seq, 1);
  EXPECT_EQ(sp.reasons, reason::kCommandDelay);
  // 599 ms: still held; 600 ms: taken
  in.now = in.command_received = in.track_received = in.vehicle_received = kT0 + 599 * kMs;
  EXPECT_DOUBLE_EQ(b.update(in).velocity[1], -0.5);
  in.now = in.command_received = in.track_received = in.vehicle_received = kT0 + 600 * kMs;
  sp = b.update(in);
  EXPECT_DOUBLE_EQ(sp.velocity[1], 0.5);
  EXPECT_EQ(sp.seq, 2);
  EXPECT_EQ(sp.reasons, 0);
}

TEST(FlightBridge, HoverIsTakenAtOnce) {
  FlightBridge b{FlightParams{}};
  BridgeInputs in = ready(fine(-0.5, 0, 1));
  b.update(in);
  in.now = in.command_received = in.track_received = in.vehicle_received = kT0 + 50 * kMs;
  in.command = GestureCommand{};
  in.command->track_id = 7;
  const Setpoint sp = b.update(in);
  EXPECT_TRUE(sp.is_zero());
  EXPECT_EQ(sp.reasons, 0);
}

TEST(FlightBridge, ZeroingForgetsTheHeldCommand) {
  FlightBridge b{FlightParams{}};
  BridgeInputs in = ready(fine(-0.5, 0, 1));
  b.update(in);
  in.engaged = false;
  b.update(in);
  // re-engaged with a fresh HOVER: no old motion comes back
  in.engaged = true;
  in.command = GestureCommand{};
  in.command->track_id = 7;
  EXPECT_TRUE(b.update(in).is_zero());
}

}  // namespace
}  // namespace gpilot
