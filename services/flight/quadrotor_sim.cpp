// QuadrotorSim: exact first-order lag per step (alpha = 1 - exp(-dt / tau)), then explicit position update.
#include "quadrotor_sim.hpp"

#include <algorithm>
#include <cmath>

namespace gpilot {
namespace {

constexpr double kGravity = 9.80665;
constexpr double kPi = 3.14159265358979323846;

double wrap_pi(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0) a += 2.0 * kPi;
  return a - kPi;
}

}  // namespace

QuadrotorSim::QuadrotorSim(const SimParams& params)
    : params_(params),
      phase_(params.start_down < 0.0 ? Phase::Flying : Phase::OnGround),
      armed_(params.start_down < 0.0),
      pos_{params.start_north, params.start_east, std::min(0.0, params.start_down)},
      yaw_(wrap_pi(params.start_yaw)) {}

void QuadrotorSim::arm() { armed_ = true; }

void QuadrotorSim::disarm() {
  if (phase_ == Phase::OnGround) armed_ = false;
}

void QuadrotorSim::takeoff(double altitude_m) {
  if (!armed_ || phase_ != Phase::OnGround || !(altitude_m > 0.0)) return;
  phase_ = Phase::Takeoff;
  takeoff_down_ = pos_[2] - altitude_m;
}

void QuadrotorSim::land() {
  if (phase_ == Phase::Flying || phase_ == Phase::Takeoff) phase_ = Phase::Landing;
}

void QuadrotorSim::step(const Setpoint& sp, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) return;
  const bool finite = std::isfinite(sp.velocity[0]) && std::isfinite(sp.velocity[1]) &&
                      std::isfinite(sp.velocity[2]) && std::isfinite(sp.yaw_rate);
  switch (phase_) {
    case Phase::Flying:
      if (finite) {
        // Body FRD -> world NED about the current yaw (the autopilot holds roll and pitch for us).
        const double c = std::cos(yaw_), s = std::sin(yaw_);
        target_[0] = c * sp.velocity[0] - s * sp.velocity[1];
        target_[1] = s * sp.velocity[0] + c * sp.velocity[1];
        target_[2] = sp.velocity[2];
        target_yaw_rate_ = sp.yaw_rate;
      }
      break;
    case Phase::Takeoff:
      target_[0] = target_[1] = 0.0;
      target_[2] = -params_.takeoff_speed;
      target_yaw_rate_ = 0.0;
      break;
    case Phase::Landing:
      target_[0] = target_[1] = 0.0;
      target_[2] = params_.land_speed;
      target_yaw_rate_ = 0.0;
      break;
    case Phase::OnGround:
      target_[0] = target_[1] = target_[2] = 0.0;
      target_yaw_rate_ = 0.0;
      break;
  }
  // The airframe's limits.
  const double h = std::hypot(target_[0], target_[1]);
  if (h > params_.max_horizontal_speed) {
    target_[0] *= params_.max_horizontal_speed / h;
    target_[1] *= params_.max_horizontal_speed / h;
  }
  target_[2] = std::clamp(target_[2], -params_.max_vertical_speed, params_.max_vertical_speed);
  target_yaw_rate_ = std::clamp(target_yaw_rate_, -params_.max_yaw_rate, params_.max_yaw_rate);

  if (phase_ == Phase::OnGround) {
    for (int i = 0; i < 3; ++i) vel_[i] = accel_[i] = 0.0;
    yaw_rate_ = 0.0;
  } else {
    const double av = 1.0 - std::exp(-dt / params_.velocity_time_constant_s);
    const double ay = 1.0 - std::exp(-dt / params_.yaw_time_constant_s);
    for (int i = 0; i < 3; ++i) {
      const double dv = av * (target_[i] - vel_[i]);
      accel_[i] = dv / dt;
      vel_[i] += dv;
      pos_[i] += vel_[i] * dt;
    }
    yaw_rate_ += ay * (target_yaw_rate_ - yaw_rate_);
    yaw_ = wrap_pi(yaw_ + yaw_rate_ * dt);
  }
  if (phase_ == Phase::Takeoff && pos_[2] <= takeoff_down_) phase_ = Phase::Flying;
  if (pos_[2] >= 0.0 && phase_ != Phase::Takeoff) {
    // The ground: touching it ends any flight; landing (or flying into it) leaves the vehicle on the ground.
    pos_[2] = 0.0;
    if (phase_ == Phase::Landing || vel_[2] > 0.0) {
      if (phase_ == Phase::Landing) armed_ = false;  // as autopilots disarm after a landing
      phase_ = Phase::OnGround;
      for (int i = 0; i < 3; ++i) vel_[i] = accel_[i] = 0.0;
      yaw_rate_ = 0.0;
    }
  }
  elapsed_s_ += dt;
  ++steps_;
}

VehicleState QuadrotorSim::state(int64_t utime) const {
  VehicleState v;
  v.utime = utime;
  v.seq = steps_;
  for (int i = 0; i < 3; ++i) {
    v.position[i] = pos_[i];
    v.velocity[i] = vel_[i];
  }
  // Tilt that would produce the horizontal acceleration: nose down to speed up forward, right side down
  // to speed up to the right.
  const double c = std::cos(yaw_), s = std::sin(yaw_);
  const double a_fwd = c * accel_[0] + s * accel_[1];
  const double a_right = -s * accel_[0] + c * accel_[1];
  v.attitude[0] = std::atan2(a_right, kGravity);
  v.attitude[1] = -std::atan2(a_fwd, kGravity);
  v.attitude[2] = yaw_;
  v.yaw_rate = yaw_rate_;
  v.armed = armed_;
  switch (phase_) {
    case Phase::OnGround: v.landed = VehicleState::Landed::OnGround; break;
    case Phase::Takeoff: v.landed = VehicleState::Landed::Takeoff; break;
    case Phase::Flying: v.landed = VehicleState::Landed::InAir; break;
    case Phase::Landing: v.landed = VehicleState::Landed::Landing; break;
  }
  return v;
}

}  // namespace gpilot
