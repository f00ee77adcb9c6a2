// QuadrotorSim: first-order response, body -> world rotation by yaw, limits, ground, take-off and landing,
// determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "quadrotor_sim.hpp"

namespace gpilot {
namespace {

constexpr double kDt = 0.01;  // 100 Hz

Setpoint body(double vx, double vy, double vz, double r = 0.0) {
  Setpoint s;
  s.velocity[0] = vx;
  s.velocity[1] = vy;
  s.velocity[2] = vz;
  s.yaw_rate = r;
  return s;
}

void run(QuadrotorSim& sim, const Setpoint& sp, double seconds) {
  const int n = static_cast<int>(std::lround(seconds / kDt));
  for (int i = 0; i < n; ++i) sim.step(sp, kDt);
}

TEST(QuadrotorSim, StartsAtTheConfiguredPoseInTheAir) {
  SimParams p;
  p.start_north = 2;
  p.start_east = -1;
  p.start_yaw = 0.5;
  QuadrotorSim sim(p);
  const VehicleState s = sim.state(123);
  EXPECT_EQ(s.utime, 123);
  EXPECT_EQ(s.position[0], 2);
  EXPECT_EQ(s.position[1], -1);
  EXPECT_EQ(s.position[2], -1.5);
  EXPECT_EQ(s.attitude[2], 0.5);
  EXPECT_TRUE(s.armed);
  EXPECT_EQ(s.landed, VehicleState::Landed::InAir);
}

TEST(QuadrotorSim, VelocityFollowsAFirstOrderLag) {
  QuadrotorSim sim{SimParams{}};  // tau 0.3 s
  run(sim, body(1, 0, 0), 0.3);
  EXPECT_NEAR(sim.state(0).velocity[0], 1.0 - std::exp(-1.0), 1e-9);  // 63.2 % after one time constant
  run(sim, body(1, 0, 0), 3.0);
  EXPECT_NEAR(sim.state(0).velocity[0], 1.0, 1e-4);
}

TEST(QuadrotorSim, BodyVelocityIsRotatedByYaw) {
  // Facing east (yaw +90 deg): body forward is east, body right is south.
  SimParams p;
  p.start_yaw = M_PI / 2;
  QuadrotorSim fwd(p), right(p);
  run(fwd, body(1, 0, 0), 5.0);
  run(right, body(0, 1, 0), 5.0);
  EXPECT_NEAR(fwd.state(0).velocity[0], 0.0, 1e-6);
  EXPECT_NEAR(fwd.state(0).velocity[1], 1.0, 1e-4);
  EXPECT_NEAR(right.state(0).velocity[0], -1.0, 1e-4);
  EXPECT_NEAR(right.state(0).velocity[1], 0.0, 1e-6);
}

TEST(QuadrotorSim, PositiveYawRateTurnsClockwiseSeenFromAbove) {
  QuadrotorSim sim{SimParams{}};
  run(sim, body(0, 0, 0, 0.5), 2.0);
  const VehicleState s = sim.state(0);
  EXPECT_GT(s.attitude[2], 0.7);  // ~0.5 * (2 - 0.15) rad, toward east
  EXPECT_LT(s.attitude[2], 0.95);
}

TEST(QuadrotorSim, AirframeLimitsApply) {
  SimParams p;
  p.max_horizontal_speed = 2.0;
  QuadrotorSim sim(p);
  run(sim, body(10, 0, 0), 5.0);
  EXPECT_NEAR(sim.state(0).velocity[0], 2.0, 1e-4);
}

TEST(QuadrotorSim, SameInputsSameTrajectory) {
  QuadrotorSim a{SimParams{}}, b{SimParams{}};
  for (int i = 0; i < 500; ++i) {
    const Setpoint sp = body(std::sin(i * 0.01), 0.3, -0.1, 0.2);
    a.step(sp, kDt);
    b.step(sp, kDt);
  }
  const VehicleState sa = a.state(0), sb = b.state(0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(sa.position[i], sb.position[i]);
  EXPECT_EQ(sa.attitude[2], sb.attitude[2]);
}

TEST(QuadrotorSim, LandsDisarmsAndTakesOffAgain) {
  QuadrotorSim sim{SimParams{}};  // 1.5 m up, land at 0.5 m/s
  sim.land();
  EXPECT_EQ(sim.state(0).landed, VehicleState::Landed::Landing);
  run(sim, body(1, 1, 0), 6.0);  // setpoints are ignored while landing
  VehicleState s = sim.state(0);
  EXPECT_EQ(s.landed, VehicleState::Landed::OnGround);
  EXPECT_EQ(s.position[2], 0.0);
  EXPECT_NEAR(s.position[0], 0.0, 1e-9);
  EXPECT_FALSE(s.armed);
  sim.takeoff(2.0);  // not armed: refused
  EXPECT_EQ(sim.state(0).landed, VehicleState::Landed::OnGround);
  sim.arm();
  sim.takeoff(2.0);
  run(sim, body(0, 0, 0), 4.0);
  s = sim.state(0);
  EXPECT_EQ(s.landed, VehicleState::Landed::InAir);
  EXPECT_LT(s.position[2], -2.0);
  EXPECT_GT(s.position[2], -2.5);
}

TEST(QuadrotorSim, NonFiniteSetpointIsIgnored) {
  QuadrotorSim sim{SimParams{}};
  run(sim, body(1, 0, 0), 1.0);
  const double v = sim.state(0).velocity[0];
  sim.step(body(NAN, 0, 0), kDt);
  EXPECT_TRUE(std::isfinite(sim.state(0).position[0]));
  EXPECT_GT(sim.state(0).velocity[0], v);  // kept the last target (1 m/s)
}

}  // namespace
}  // namespace gpilot
