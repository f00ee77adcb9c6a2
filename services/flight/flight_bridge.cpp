// FlightBridge: scaling, camera -> body frame, yaw to face the user, the 600 ms spacing and the safety rules.
#include "flight_bridge.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "clock.hpp"

namespace gpilot {
namespace {

bool finite_all(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

bool same_command(const GestureCommand& a, const GestureCommand& b) {
  return a.mode == b.mode && a.direction[0] == b.direction[0] && a.direction[1] == b.direction[1] &&
         a.direction[2] == b.direction[2];
}

}  // namespace

FlightBridge::FlightBridge(const FlightParams& params) : params_(params) {}

std::string FlightBridge::check_command(const GestureCommand& c) const {
  const double* d = c.direction;
  if (!finite_all(d, 3) || !std::isfinite(c.user_box_width)) return "command is not finite";
  const int m = static_cast<int>(c.mode);
  if (m < static_cast<int>(GestureMode::Hover) || m > static_cast<int>(GestureMode::Further))
    return "command mode " + std::to_string(m) + " is not known";
  if (std::fabs(d[0]) > params_.max_command_magnitude || std::fabs(d[1]) > params_.max_command_magnitude)
    return "command vector longer than max_command_magnitude box widths";
  switch (c.mode) {
    case GestureMode::Hover:
      if (d[0] != 0.0 || d[1] != 0.0 || d[2] != 0.0) return "HOVER command with a non-zero direction";
      break;
    case GestureMode::Fine:
    case GestureMode::Up:
    case GestureMode::Down:
      if (d[2] != 0.0) return "FINE/UP/DOWN command with a z component";
      if (c.user_box_width <= 0.0) return "FINE/UP/DOWN command without a user box width";
      if (c.mode != GestureMode::Fine && d[0] != 0.0) return "UP/DOWN command with an x component";
      if ((c.mode == GestureMode::Up && d[1] >= 0.0) || (c.mode == GestureMode::Down && d[1] <= 0.0))
        return "UP/DOWN command whose y points the other way";
      break;
    case GestureMode::Closer:
    case GestureMode::Further:
      if (d[0] != 0.0 || d[1] != 0.0 || d[2] != (c.mode == GestureMode::Closer ? 1.0 : -1.0))
        return "CLOSER/FURTHER command whose direction is not (0, 0, +-1)";
      break;
  }
  return "";
}

std::string FlightBridge::check_track(const UserTrack& t) {
  if (!finite_all(t.box, 4)) return "user box is not finite";
  if (t.box[2] <= 0.0 || t.box[3] <= 0.0) return "user box has no area";
  if (t.image_width <= 0) return "track without an image width";
  const double cx = t.box[0] + t.box[2] / 2.0;
  if (cx < 0.0 || cx > t.image_width) return "user box centre outside the image";
  return "";
}

std::string FlightBridge::check_vehicle(const VehicleState& v) {
  if (!finite_all(v.position, 3) || !finite_all(v.velocity, 3) || !finite_all(v.attitude, 3) ||
      !std::isfinite(v.yaw_rate))
    return "vehicle state is not finite";
  return "";
}

void FlightBridge::command_velocity(const FlightParams& p, const GestureCommand& c, double body[3]) {
  const double cam[3] = {p.gain_horizontal * c.direction[0], p.gain_vertical * c.direction[1],
                         p.speed_along_axis * c.direction[2]};
  body[0] = cam[2];
  body[1] = cam[0];
  body[2] = cam[1];
}

double FlightBridge::yaw_rate_for(const FlightParams& p, const UserTrack& t) {
  // > 0 when the user is right of the image centre: turn right (clockwise from above) to bring them back.
  const double offset = (t.box[0] + t.box[2] / 2.0) / t.image_width - 0.5;
  if (std::fabs(offset) <= p.yaw_deadband) return 0.0;
  return p.yaw_gain * offset;
}

Setpoint FlightBridge::update(const BridgeInputs& in) {
  Setpoint sp;
  sp.utime = in.now;
  sp.engaged = in.engaged;
  sp.mode = static_cast<int8_t>(GestureMode::Hover);
  if (in.command) sp.seq = sp.latest_command_seq = in.command->seq;
  if (in.track) sp.track_utime = in.track->utime;

  int32_t zero = 0;
  if (in.landing) zero |= reason::kLanding;
  if (!in.engaged) zero |= reason::kNotEngaged;
  const bool need_vehicle = params_.require_vehicle_state;
  if (!in.command || !in.track || (need_vehicle && !in.vehicle)) zero |= reason::kStartup;
  const int64_t stale = seconds_to_utime(params_.stale_timeout_s);
  if (in.command && in.now - in.command_received > stale) zero |= reason::kStaleCommand;
  if (in.track && in.now - in.track_received > stale) zero |= reason::kStaleTrack;
  if (need_vehicle && in.vehicle && in.now - in.vehicle_received > stale) zero |= reason::kStaleVehicle;
  if (in.track && !in.track->tracking) zero |= reason::kTrackLost;
  // A command made for another user (the tracker started a new track since) is not flown.
  if (in.command && in.track && in.command->track_id != in.track->track_id) zero |= reason::kTrackLost;

  last_invalid_.clear();
  if (in.command) last_invalid_ = check_command(*in.command);
  if (last_invalid_.empty() && in.track) last_invalid_ = check_track(*in.track);
  if (last_invalid_.empty() && in.vehicle) last_invalid_ = check_vehicle(*in.vehicle);
  if (!last_invalid_.empty()) zero |= reason::kInvalidInput;

  if (zero) {
    // Nothing held survives a zeroing: the next motion starts from a fresh command.
    flown_ = GestureCommand{};
    sp.reasons = zero;
    return sp;
  }

  const GestureCommand& latest = *in.command;
  if (!same_command(latest, flown_)) {
    const bool spaced = !have_adopted_ || in.now - adopted_at_ >= seconds_to_utime(params_.command_spacing_s);
    if (latest.mode == GestureMode::Hover || spaced) {
      flown_ = latest;
      have_adopted_ = true;
      adopted_at_ = in.now;
    } else {
      sp.reasons |= reason::kCommandDelay;
    }
  }
  sp.seq = flown_.seq;
  sp.mode = static_cast<int8_t>(flown_.mode);

  command_velocity(params_, flown_, sp.velocity);
  const double h = std::hypot(sp.velocity[0], sp.velocity[1]);
  if (h > params_.max_horizontal_speed) {
    const double k = params_.max_horizontal_speed / h;
    sp.velocity[0] *= k;
    sp.velocity[1] *= k;
    sp.reasons |= reason::kClipped;
  }
  if (std::fabs(sp.velocity[2]) > params_.max_vertical_speed) {
    sp.velocity[2] = std::copysign(params_.max_vertical_speed, sp.velocity[2]);
    sp.reasons |= reason::kClipped;
  }
  if (in.vehicle) {
    const double height = -in.vehicle->position[2];  // NED down; body z is down too
    if ((sp.velocity[2] < 0 && height >= params_.max_height_m) || (sp.velocity[2] > 0 && height <= params_.min_height_m)) {
      sp.velocity[2] = 0.0;
      sp.reasons |= reason::kHeightLimit;
    }
  }
  const UserTrack& t = *in.track;
  if (params_.keep_face_in_view && t.image_height > 0) {
    const double face_top = t.box[1], face_bottom = t.box[1] + params_.face_band_ratio * t.box[3];
    bool held = false;
    if (face_top <= 0.0 && (sp.velocity[2] > 0 || sp.velocity[0] > 0)) {  // at the top: no descent, no closer
      sp.velocity[2] = std::min(sp.velocity[2], 0.0);
      sp.velocity[0] = std::min(sp.velocity[0], 0.0);
      held = true;
    }
    if (face_bottom >= t.image_height && sp.velocity[2] < 0) {  // at the bottom: no climb
      sp.velocity[2] = 0.0;
      held = true;
    }
    if (held) sp.reasons |= reason::kViewLimit;
  }
  // The user box's point view_box_ratio of its height below its top is at or below the image's bottom edge: climbing
  // or closing in would cut the hips and the hanging hands.
  const bool at_bottom = t.image_height > 0 && params_.view_box_ratio > 0 &&
                         t.box[1] + params_.view_box_ratio * t.box[3] >= t.image_height;
  if (at_bottom && sp.velocity[2] < 0) {  // hands cut: no climb
    sp.velocity[2] = 0.0;
    sp.reasons |= reason::kViewLimit;
  }
  const bool fills_image = params_.closest_box_height_ratio > 0 && t.box[3] >= params_.closest_box_height_ratio * t.image_height;
  if (t.image_height > 0 && sp.velocity[0] > 0 && (fills_image || at_bottom)) {
    sp.velocity[0] = 0.0;
    sp.reasons |= reason::kRangeLimit;
  }
  sp.yaw_rate = yaw_rate_for(params_, *in.track);
  if (std::fabs(sp.yaw_rate) > params_.max_yaw_rate) {
    sp.yaw_rate = std::copysign(params_.max_yaw_rate, sp.yaw_rate);
    sp.reasons |= reason::kClipped;
  }
  return sp;
}

}  // namespace gpilot
