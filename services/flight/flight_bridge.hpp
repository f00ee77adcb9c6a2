// FlightBridge: the flight stage's core. Latest gesture command, user track and vehicle state (each with its
// receipt time), the operator's engage/land state and the time now in; one body-frame velocity setpoint out,
// with a bit for every rule that zeroed or clipped it. The only thing in the system that asks for motion.
#pragma once

#include <optional>

#include "decide/gesture_command.hpp"
#include "flight_params.hpp"
#include "flight_types.hpp"

namespace gpilot {

struct BridgeInputs {
  int64_t now = 0;  //!< us, the same clock as the receipt times
  std::optional<GestureCommand> command;
  int64_t command_received = 0;
  std::optional<UserTrack> track;
  int64_t track_received = 0;
  std::optional<VehicleState> vehicle;
  int64_t vehicle_received = 0;
  bool engaged = false;
  bool landing = false;
};

class FlightBridge {
 public:
  explicit FlightBridge(const FlightParams& params);

  // Zero (hover) unless engaged, not landing, every input present, fresh (<= stale_timeout_s), valid and the
  // track TRACKING. A changed command is taken at most once per command_spacing_s (0.3 s; the paper's 600 ms); a
  // change to HOVER is taken at once (stopping is never delayed).
  Setpoint update(const BridgeInputs& in);

  // Camera-frame command -> body FRD velocity, before limits (x_body = z_cam, y_body = x_cam, z_body = y_cam).
  static void command_velocity(const FlightParams& p, const GestureCommand& c, double body[3]);
  // Yaw rate that centres the user box horizontally: P on (box centre / image width - 0.5), dead band, no limit.
  static double yaw_rate_for(const FlightParams& p, const UserTrack& t);

  // Why the inputs are invalid ("" when they are fine): NaN, out of range, a mode inconsistent with its vector.
  std::string check_command(const GestureCommand& c) const;
  static std::string check_track(const UserTrack& t);
  static std::string check_vehicle(const VehicleState& v);
  const std::string& last_invalid() const { return last_invalid_; }

 private:
  FlightParams params_;
  GestureCommand flown_;        // the command being flown (held between adoptions)
  bool have_adopted_ = false;
  int64_t adopted_at_ = 0;
  std::string last_invalid_;
};

}  // namespace gpilot
