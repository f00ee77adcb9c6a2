// LCM messages <-> the flight core's types (see flight_messages.hpp).
#include "flight_messages.hpp"

namespace gpilot {

static_assert(reason::kNotEngaged == flight_setpoint_t::REASON_NOT_ENGAGED &&
                  reason::kStartup == flight_setpoint_t::REASON_STARTUP &&
                  reason::kStaleCommand == flight_setpoint_t::REASON_STALE_COMMAND &&
                  reason::kStaleTrack == flight_setpoint_t::REASON_STALE_TRACK &&
                  reason::kStaleVehicle == flight_setpoint_t::REASON_STALE_VEHICLE &&
                  reason::kTrackLost == flight_setpoint_t::REASON_TRACK_LOST &&
                  reason::kInvalidInput == flight_setpoint_t::REASON_INVALID_INPUT &&
                  reason::kCommandDelay == flight_setpoint_t::REASON_COMMAND_DELAY &&
                  reason::kClipped == flight_setpoint_t::REASON_CLIPPED &&
                  reason::kLanding == flight_setpoint_t::REASON_LANDING &&
                  reason::kHeightLimit == flight_setpoint_t::REASON_HEIGHT_LIMIT &&
                  reason::kViewLimit == flight_setpoint_t::REASON_VIEW_LIMIT &&
                  reason::kRangeLimit == flight_setpoint_t::REASON_RANGE_LIMIT,
              "reason bits and flight_setpoint_t::REASON_* must agree");
static_assert(static_cast<int>(VehicleState::Landed::Landing) == vehicle_state_t::LANDED_LANDING &&
                  static_cast<int>(VehicleState::Landed::InAir) == vehicle_state_t::LANDED_IN_AIR,
              "VehicleState::Landed and vehicle_state_t::LANDED_* must agree");

GestureCommand to_core(const gesture_cmd_t& m) {
  GestureCommand c;
  c.utime = m.utime;
  c.seq = m.seq;
  c.track_id = m.track_id;
  c.mode = static_cast<GestureMode>(m.mode);
  for (int i = 0; i < 3; ++i) c.direction[i] = m.direction[i];
  c.user_box_width = m.user_box_width;
  return c;
}

UserTrack to_core(const user_track_t& m) {
  UserTrack t;
  t.utime = m.utime;
  t.tracking = m.status == user_track_t::STATUS_TRACKING;
  for (int i = 0; i < 4; ++i) t.box[i] = m.box[i];
  t.track_id = m.track_id;
  t.image_width = m.image_width;
  t.image_height = m.image_height;
  return t;
}

VehicleState to_core(const vehicle_state_t& m) {
  VehicleState v;
  v.utime = m.utime;
  v.seq = m.seq;
  for (int i = 0; i < 3; ++i) {
    v.position[i] = m.position[i];
    v.velocity[i] = m.velocity[i];
    v.attitude[i] = m.attitude[i];
  }
  v.yaw_rate = m.yaw_rate;
  v.armed = m.armed;
  v.landed = static_cast<VehicleState::Landed>(m.landed_state);
  return v;
}

vehicle_state_t to_message(const VehicleState& v, int8_t source) {
  vehicle_state_t m{};
  m.utime = v.utime;
  m.seq = v.seq;
  for (int i = 0; i < 3; ++i) {
    m.position[i] = static_cast<float>(v.position[i]);
    m.velocity[i] = static_cast<float>(v.velocity[i]);
    m.attitude[i] = static_cast<float>(v.attitude[i]);
  }
  m.yaw_rate = static_cast<float>(v.yaw_rate);
  m.armed = v.armed;
  m.source = source;
  m.landed_state = static_cast<int8_t>(v.landed);
  return m;
}

flight_setpoint_t to_message(const Setpoint& s) {
  flight_setpoint_t m{};
  m.utime = s.utime;
  m.seq = s.seq;
  for (int i = 0; i < 3; ++i) m.velocity[i] = static_cast<float>(s.velocity[i]);
  m.yaw_rate = static_cast<float>(s.yaw_rate);
  m.engaged = s.engaged;
  m.mode = s.mode;
  m.reasons = s.reasons;
  m.latest_command_seq = s.latest_command_seq;
  m.track_utime = s.track_utime;
  return m;
}

static_assert(static_cast<int>(OperatorCommand::Engage) == flight_control_t::COMMAND_ENGAGE &&
                  static_cast<int>(OperatorCommand::Disengage) == flight_control_t::COMMAND_DISENGAGE &&
                  static_cast<int>(OperatorCommand::Arm) == flight_control_t::COMMAND_ARM &&
                  static_cast<int>(OperatorCommand::Takeoff) == flight_control_t::COMMAND_TAKEOFF &&
                  static_cast<int>(OperatorCommand::Land) == flight_control_t::COMMAND_LAND &&
                  static_cast<int>(OperatorCommand::Disarm) == flight_control_t::COMMAND_DISARM,
              "OperatorCommand and flight_control_t::COMMAND_* must agree");

OperatorRequest to_core(const flight_control_t& m) {
  OperatorRequest r;
  r.utime = m.utime;
  r.seq = m.seq;
  r.source = m.source;
  r.command = m.command;
  r.takeoff_altitude = m.takeoff_altitude;
  return r;
}

AutopilotMessage to_core(const autopilot_t& m) {
  AutopilotMessage a;
  a.kind = m.kind == autopilot_t::KIND_PARAM_VALUE ? AutopilotMessage::Kind::ParamValue : AutopilotMessage::Kind::Heartbeat;
  a.armed = m.armed;
  a.base_mode = m.base_mode;
  a.custom_mode = m.custom_mode;
  a.system_status = m.system_status;
  a.param_id = m.param_id;
  a.param_value = m.param_value;
  a.param_type = m.param_type;
  return a;
}

autopilot_t to_message(const mavlink::Heartbeat& h, int64_t utime) {
  autopilot_t m{};
  m.utime = utime;
  m.kind = autopilot_t::KIND_HEARTBEAT;
  m.armed = (h.base_mode & mavlink::kMavModeFlagSafetyArmed) != 0;
  m.base_mode = h.base_mode;
  m.custom_mode = h.custom_mode;
  m.system_status = static_cast<int8_t>(h.system_status);
  return m;
}

autopilot_t to_message(const mavlink::ParamValue& v, int64_t utime) {
  autopilot_t m{};
  m.utime = utime;
  m.kind = autopilot_t::KIND_PARAM_VALUE;
  m.param_id = mavlink::param_name(v.param_id);
  m.param_value = v.param_value;
  m.param_type = static_cast<int8_t>(v.param_type);
  return m;
}

}  // namespace gpilot
