// QuadrotorSim: the built-in simulator. A point mass whose world velocity and yaw rate follow the body-frame
// setpoint through first-order lags (time constants and limits in SimParams), with a ground, arming, take-off
// and landing. Deterministic: the state depends only on the start pose and the sequence of step() inputs.
#pragma once

#include "flight_params.hpp"
#include "flight_types.hpp"

namespace gpilot {

class QuadrotorSim {
 public:
  // Starts at the configured pose: armed and in the air when start_down < 0, else disarmed on the ground.
  explicit QuadrotorSim(const SimParams& params);

  // Advances dt seconds following the setpoint (body FRD velocity, yaw rate). Non-finite setpoints or dt are
  // ignored (the vehicle keeps its last targets), as an autopilot drops a malformed setpoint.
  void step(const Setpoint& setpoint, double dt);

  // The operator's requests. takeoff needs armed and on the ground; land works from the air.
  void arm();
  void disarm();  // only on the ground
  void takeoff(double altitude_m);
  void land();

  // The state now; utime is the caller's clock, seq counts steps.
  VehicleState state(int64_t utime) const;
  double elapsed_s() const { return elapsed_s_; }

 private:
  enum class Phase { OnGround, Takeoff, Flying, Landing };

  SimParams params_;
  Phase phase_;
  bool armed_;
  double pos_[3];
  double vel_[3] = {0.0, 0.0, 0.0};
  double accel_[3] = {0.0, 0.0, 0.0};
  double yaw_;
  double yaw_rate_ = 0.0;
  double takeoff_down_ = 0.0;  // NED down of the take-off target
  double target_[3] = {0.0, 0.0, 0.0};  // last world-velocity target
  double target_yaw_rate_ = 0.0;
  double elapsed_s_ = 0.0;
  int64_t steps_ = 0;
};

}  // namespace gpilot
