// MavlinkSession: frames out (sequence numbers, ids, type mask) and vehicle state in.
#include "session.hpp"

#include <cmath>

namespace gpilot::mavlink {

MavlinkSession::MavlinkSession(const MavlinkParams& params) : params_(params) {
  state_.landed = VehicleState::Landed::Unknown;
}

void MavlinkSession::enable_signing(const std::array<uint8_t, 32>& key, uint8_t link_id) {
  signer_.emplace(key, link_id);
  checker_.emplace(key);
  parser_.require_signatures(&*checker_);
}

template <class M>
std::vector<uint8_t> MavlinkSession::frame(const M& m) {
  Frame f;
  f.seq = seq_++;
  f.sysid = static_cast<uint8_t>(params_.system_id);
  f.compid = static_cast<uint8_t>(params_.component_id);
  f.msgid = M::kId;
  f.payload = pack(m);
  std::vector<uint8_t> bytes = encode_frame(f);
  if (signer_) signer_->sign(bytes, message_info(M::kId)->crc_extra, now_);
  return bytes;
}

uint32_t MavlinkSession::boot_ms(int64_t now_utime) {
  if (!have_boot_) {
    have_boot_ = true;
    boot_utime_ = now_utime;
  }
  return static_cast<uint32_t>((now_utime - boot_utime_) / 1000);
}

std::vector<uint8_t> MavlinkSession::heartbeat() {
  Heartbeat h;
  h.type = kMavTypeOnboardController;
  h.autopilot = kMavAutopilotInvalid;
  h.system_status = kMavStateActive;
  return frame(h);
}

std::vector<uint8_t> MavlinkSession::setpoint(const Setpoint& sp, int64_t now_utime) {
  set_time(now_utime);
  SetPositionTargetLocalNed m;
  m.time_boot_ms = boot_ms(now_utime);
  m.vx = static_cast<float>(sp.velocity[0]);
  m.vy = static_cast<float>(sp.velocity[1]);
  m.vz = static_cast<float>(sp.velocity[2]);
  m.yaw_rate = static_cast<float>(sp.yaw_rate);
  m.type_mask = kTypeMaskVelocityYawRate;
  m.target_system = static_cast<uint8_t>(params_.target_system);
  m.target_component = static_cast<uint8_t>(params_.target_component);
  m.coordinate_frame = kMavFrameBodyNed;
  return frame(m);
}

std::vector<uint8_t> MavlinkSession::command_long(uint16_t command, const float (&param)[7]) {
  CommandLong m;
  for (int i = 0; i < 7; ++i) m.param[i] = param[i];
  m.command = command;
  m.target_system = static_cast<uint8_t>(params_.target_system);
  m.target_component = static_cast<uint8_t>(params_.target_component);
  return frame(m);
}

std::vector<uint8_t> MavlinkSession::arm(bool on) {
  return command_long(kMavCmdComponentArmDisarm, {on ? 1.0f : 0.0f, 0, 0, 0, 0, 0, 0});
}

std::vector<uint8_t> MavlinkSession::takeoff(float altitude_m) {
  const float nan = std::nanf("");
  // NaN: "use the autopilot's default" for yaw, latitude and longitude (and PX4's altitude, see the header).
  return command_long(kMavCmdNavTakeoff, {0, 0, 0, nan, nan, nan, ardupilot() ? altitude_m : nan});
}

std::vector<uint8_t> MavlinkSession::land() {
  const float nan = std::nanf("");
  return command_long(kMavCmdNavLand, {0, 0, 0, nan, nan, nan, nan});
}

std::vector<uint8_t> MavlinkSession::engage_mode() {
  const float mode = ardupilot() ? kArduCopterModeGuided : kPx4CustomMainModeOffboard;
  return command_long(kMavCmdDoSetMode, {kMavModeFlagCustomModeEnabled, mode, 0, 0, 0, 0, 0});
}

std::vector<uint8_t> MavlinkSession::param_request_read(const std::string& name) {
  ParamRequestRead m;
  m.param_index = -1;
  m.target_system = static_cast<uint8_t>(params_.target_system);
  m.target_component = static_cast<uint8_t>(params_.target_component);
  for (size_t i = 0; i < name.size() && i < sizeof m.param_id; ++i) m.param_id[i] = name[i];
  return frame(m);
}

std::optional<VehicleState> MavlinkSession::on_datagram(const uint8_t* data, size_t n, int64_t receive_utime) {
  std::optional<VehicleState> out;
  set_time(receive_utime);
  if (checker_) checker_->set_now(receive_utime);
  parser_.feed(data, n, [&](const Frame& f) {
    if (f.sysid != params_.target_system) {
      ++other_system_;
      return;
    }
    switch (f.msgid) {
      case Heartbeat::kId: {
        const Heartbeat h = unpack_heartbeat(f.payload);
        // A GCS or camera on the same system id also sends HEARTBEAT: only the autopilot's says armed.
        if (h.autopilot == kMavAutopilotInvalid) return;
        heard_ = true;
        state_.armed = (h.base_mode & kMavModeFlagSafetyArmed) != 0;
        heartbeats_.push_back(h);
        break;
      }
      case Attitude::kId: {
        const Attitude a = unpack_attitude(f.payload);
        state_.attitude[0] = a.roll;
        state_.attitude[1] = a.pitch;
        state_.attitude[2] = a.yaw;
        state_.yaw_rate = a.yawspeed;
        break;
      }
      case ExtendedSysState::kId: {
        const ExtendedSysState e = unpack_extended_sys_state(f.payload);
        state_.landed = e.landed_state <= 4 ? static_cast<VehicleState::Landed>(e.landed_state)
                                            : VehicleState::Landed::Unknown;
        break;
      }
      case CommandAck::kId: last_ack_ = unpack_command_ack(f.payload); break;
      case ParamValue::kId: param_values_.push_back(unpack_param_value(f.payload)); break;
      case LocalPositionNed::kId: {
        const LocalPositionNed p = unpack_local_position_ned(f.payload);
        state_.position[0] = p.x;
        state_.position[1] = p.y;
        state_.position[2] = p.z;
        state_.velocity[0] = p.vx;
        state_.velocity[1] = p.vy;
        state_.velocity[2] = p.vz;
        state_.utime = receive_utime;
        state_.seq = ++state_seq_;
        out = state_;
        break;
      }
      default: break;  // our own kinds of message echoed back (COMMAND_LONG, setpoints): nothing to read
    }
  });
  parser_.end_of_datagram();
  return out;
}

}  // namespace gpilot::mavlink
