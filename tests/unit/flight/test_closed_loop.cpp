// Direction, end to end through the cores: hand observations -> GestureDecider -> FlightBridge -> QuadrotorSim,
// time stepped by hand (hand observations at 25 fps, setpoints at 50 Hz, simulator at 100 Hz). A pinhole camera
// on the simulated drone sees the user, so the user box (and the yaw that keeps it centred) follows the vehicle.
//
// The scene: the drone starts at the origin, 1.5 m up, yaw 0 (facing north). The user stands 4 m north of it,
// facing the drone, that is facing south. The user's right is then WEST. A user pointing to their right puts
// the hand on the image's left (vector x < 0); the command is camera -x = body -y = west (yaw 0, the camera's
// +x is east): the drone moves west, to the user's right, as they meant.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "flight_bridge.hpp"
#include "gesture_decider.hpp"
#include "quadrotor_sim.hpp"

namespace gpilot {
namespace {

constexpr int64_t kT0 = 1700000000000000;
constexpr double kFocalPx = 500.0;
constexpr int kImageWidth = 640;
constexpr double kUserNorth = 4.0;
constexpr double kUserWidthM = 0.5;

// What one frame shows: the hand vector in user-box widths (image axes) and which algorithm found it.
struct Gesture {
  HandObservation::Kind kind = HandObservation::Kind::None;
  Vec2 in_box_widths;
};

class ClosedLoop {
 public:
  // The paper's Alg. 3: the distances below are set by its 1.24 s buffer.
  ClosedLoop() : decider_(paper_rule()), bridge_(FlightParams{}), sim_(SimParams{}) {}
  static DecideParams paper_rule() {
    DecideParams p;
    p.rule = "paper";
    return p;
  }

  // Runs `seconds` with the user holding `g`; returns the vehicle state at the end.
  VehicleState run(double seconds, const Gesture& g) {
    const int ticks = static_cast<int>(std::lround(seconds * 100));
    for (int i = 0; i < ticks; ++i, ++tick_) {
      const int64_t now = kT0 + tick_ * 10000;
      in_.now = now;
      if (tick_ % 4 == 0) see_frame(now, g);
      if (tick_ % 2 == 0) setpoint_ = bridge_.update(in_);
      sim_.step(setpoint_, 0.01);
      in_.vehicle = sim_.state(now);
      in_.vehicle_received = now;
    }
    return sim_.state(kT0 + tick_ * 10000);
  }

  double distance_to_user() const {
    const VehicleState s = sim_.state(0);
    return std::hypot(kUserNorth - s.position[0], 0.0 - s.position[1]);
  }

  int32_t reasons_seen = 0;

 private:
  void see_frame(int64_t now, const Gesture& g) {
    // Pinhole projection of the user (a 0.5 m wide column at (4, 0)) into the drone's camera.
    const VehicleState s = sim_.state(now);
    const double c = std::cos(s.attitude[2]), sn = std::sin(s.attitude[2]);
    const double dn = kUserNorth - s.position[0], de = 0.0 - s.position[1];
    const double fwd = c * dn + sn * de, right = -sn * dn + c * de;
    const double width = kFocalPx * kUserWidthM / fwd;
    const double centre_x = kImageWidth / 2.0 + kFocalPx * right / fwd;

    UserTrack t;
    t.utime = now;
    t.tracking = true;
    t.box[0] = centre_x - width / 2;
    t.box[1] = 100;
    t.box[2] = width;
    t.box[3] = 3.4 * width;
    t.track_id = 1;
    t.image_width = kImageWidth;
    in_.track = t;
    in_.track_received = now;

    HandObservation o;
    o.utime = now;
    o.seq = seq_++;
    o.track_id = 1;
    o.kind = g.kind;
    o.vector = {g.in_box_widths.x * width, g.in_box_widths.y * width};
    o.user_box_width = width;
    in_.command = decider_.update(o);
    in_.command_received = now;
  }

  GestureDecider decider_;
  FlightBridge bridge_;
  QuadrotorSim sim_;
  BridgeInputs in_{};
  Setpoint setpoint_;
  int64_t tick_ = 0;
  int64_t seq_ = 0;

 public:
  void engage() { in_.engaged = true; }
};

const Gesture kRest{};
const Gesture kPointUsersRight{HandObservation::Kind::Out, {-0.5, 0.0}};  // hand on the image's left
const Gesture kArmUp{HandObservation::Kind::Out, {0.1, -0.6}};
const Gesture kFrontHigh{HandObservation::Kind::Front, {0.02, -0.15}};
const Gesture kFrontLow{HandObservation::Kind::Front, {0.02, 0.15}};

TEST(ClosedLoop, PointingToTheUsersRightMovesTheDroneToTheUsersRight) {
  ClosedLoop loop;
  loop.engage();
  const VehicleState start = loop.run(1.0, kRest);
  const VehicleState end = loop.run(3.0, kPointUsersRight);
  const double west = -(end.position[1] - start.position[1]);
  const double north = end.position[0] - start.position[0];
  EXPECT_GT(west, 0.3);                // ~1.7 s at up to 0.5 m/s after the 1.24 s buffer
  EXPECT_LT(west, 1.2);
  EXPECT_LT(std::fabs(north), 0.15);   // sideways, not toward or away from the user
  EXPECT_LT(std::fabs(end.position[2] - start.position[2]), 0.02);
  EXPECT_GT(end.attitude[2], 0.0);     // yawed right (clockwise) to keep the user, now to the east, centred
}

TEST(ClosedLoop, ArmUpClimbs) {
  ClosedLoop loop;
  loop.engage();
  const VehicleState start = loop.run(1.0, kRest);
  const VehicleState end = loop.run(3.0, kArmUp);
  EXPECT_LT(end.position[2] - start.position[2], -0.3);  // NED down decreases: higher
  EXPECT_LT(std::hypot(end.position[0] - start.position[0], end.position[1] - start.position[1]), 0.02);
}

TEST(ClosedLoop, CloserShrinksTheDistanceToTheUser) {
  ClosedLoop loop;
  loop.engage();
  loop.run(1.0, kRest);
  const double before = loop.distance_to_user();
  loop.run(3.0, kFrontHigh);
  EXPECT_LT(loop.distance_to_user(), before - 0.3);
}

TEST(ClosedLoop, FurtherGrowsTheDistanceToTheUser) {
  ClosedLoop loop;
  loop.engage();
  loop.run(1.0, kRest);
  const double before = loop.distance_to_user();
  loop.run(3.0, kFrontLow);
  EXPECT_GT(loop.distance_to_user(), before + 0.3);
}

TEST(ClosedLoop, RestStaysWithinFiveCentimetres) {
  ClosedLoop loop;
  loop.engage();
  const VehicleState start = loop.run(0.1, kRest);
  const VehicleState end = loop.run(5.0, kRest);
  double d = 0;
  for (int i = 0; i < 3; ++i) d += (end.position[i] - start.position[i]) * (end.position[i] - start.position[i]);
  EXPECT_LT(std::sqrt(d), 0.05);
}

TEST(ClosedLoop, NotEngagedPointingDoesNotMove) {
  ClosedLoop loop;
  const VehicleState start = loop.run(1.0, kRest);
  const VehicleState end = loop.run(3.0, kPointUsersRight);
  EXPECT_EQ(end.position[0], start.position[0]);
  EXPECT_EQ(end.position[1], start.position[1]);
}

}  // namespace
}  // namespace gpilot
