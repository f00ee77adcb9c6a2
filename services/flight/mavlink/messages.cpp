// The few MAVLink messages gpilot uses: table of ids / CRC_EXTRA / lengths, pack and unpack in wire order.
#include "messages.hpp"

#include "wire.hpp"

namespace gpilot::mavlink {
namespace {

// CRC_EXTRA and lengths from the MAVLink common.xml / minimal.xml definitions.
constexpr MessageInfo kMessages[] = {
    {Heartbeat::kId, "HEARTBEAT", 50, 9},
    {Attitude::kId, "ATTITUDE", 39, 28},
    {LocalPositionNed::kId, "LOCAL_POSITION_NED", 185, 28},
    {CommandLong::kId, "COMMAND_LONG", 152, 33},
    {CommandAck::kId, "COMMAND_ACK", 143, 10},
    {SetPositionTargetLocalNed::kId, "SET_POSITION_TARGET_LOCAL_NED", 143, 53},
    {ExtendedSysState::kId, "EXTENDED_SYS_STATE", 130, 2},
    {ParamRequestRead::kId, "PARAM_REQUEST_READ", 214, 20},
    {ParamValue::kId, "PARAM_VALUE", 220, 25},
};

}  // namespace

const MessageInfo* message_info(uint32_t id) {
  for (const auto& m : kMessages)
    if (m.id == id) return &m;
  return nullptr;
}

std::vector<uint8_t> pack(const Heartbeat& m) {
  std::vector<uint8_t> p;
  Writer(p).u32(m.custom_mode).u8(m.type).u8(m.autopilot).u8(m.base_mode).u8(m.system_status).u8(m.mavlink_version);
  return p;
}

std::vector<uint8_t> pack(const Attitude& m) {
  std::vector<uint8_t> p;
  Writer(p).u32(m.time_boot_ms).f32(m.roll).f32(m.pitch).f32(m.yaw).f32(m.rollspeed).f32(m.pitchspeed).f32(
      m.yawspeed);
  return p;
}

std::vector<uint8_t> pack(const LocalPositionNed& m) {
  std::vector<uint8_t> p;
  Writer(p).u32(m.time_boot_ms).f32(m.x).f32(m.y).f32(m.z).f32(m.vx).f32(m.vy).f32(m.vz);
  return p;
}

std::vector<uint8_t> pack(const CommandLong& m) {
  std::vector<uint8_t> p;
  Writer w(p);
  for (float v : m.param) w.f32(v);
  w.u16(m.command).u8(m.target_system).u8(m.target_component).u8(m.confirmation);
  return p;
}

std::vector<uint8_t> pack(const CommandAck& m) {
  std::vector<uint8_t> p;
  Writer(p).u16(m.command).u8(m.result).u8(m.progress).i32(m.result_param2).u8(m.target_system).u8(
      m.target_component);
  return p;
}

std::vector<uint8_t> pack(const SetPositionTargetLocalNed& m) {
  std::vector<uint8_t> p;
  Writer(p)
      .u32(m.time_boot_ms)
      .f32(m.x).f32(m.y).f32(m.z)
      .f32(m.vx).f32(m.vy).f32(m.vz)
      .f32(m.afx).f32(m.afy).f32(m.afz)
      .f32(m.yaw).f32(m.yaw_rate)
      .u16(m.type_mask).u8(m.target_system).u8(m.target_component).u8(m.coordinate_frame);
  return p;
}

std::vector<uint8_t> pack(const ExtendedSysState& m) {
  std::vector<uint8_t> p;
  Writer(p).u8(m.vtol_state).u8(m.landed_state);
  return p;
}

std::vector<uint8_t> pack(const ParamRequestRead& m) {
  std::vector<uint8_t> p;
  Writer w(p);
  w.u16(static_cast<uint16_t>(m.param_index)).u8(m.target_system).u8(m.target_component);
  for (char c : m.param_id) w.u8(static_cast<uint8_t>(c));
  return p;
}

std::vector<uint8_t> pack(const ParamValue& m) {
  std::vector<uint8_t> p;
  Writer w(p);
  w.f32(m.param_value).u16(m.param_count).u16(m.param_index);
  for (char c : m.param_id) w.u8(static_cast<uint8_t>(c));
  w.u8(m.param_type);
  return p;
}

Heartbeat unpack_heartbeat(const std::vector<uint8_t>& p) {
  Reader r(p);
  Heartbeat m;
  m.custom_mode = r.u32();
  m.type = r.u8();
  m.autopilot = r.u8();
  m.base_mode = r.u8();
  m.system_status = r.u8();
  m.mavlink_version = r.u8();
  return m;
}

Attitude unpack_attitude(const std::vector<uint8_t>& p) {
  Reader r(p);
  Attitude m;
  m.time_boot_ms = r.u32();
  m.roll = r.f32();
  m.pitch = r.f32();
  m.yaw = r.f32();
  m.rollspeed = r.f32();
  m.pitchspeed = r.f32();
  m.yawspeed = r.f32();
  return m;
}

LocalPositionNed unpack_local_position_ned(const std::vector<uint8_t>& p) {
  Reader r(p);
  LocalPositionNed m;
  m.time_boot_ms = r.u32();
  m.x = r.f32();
  m.y = r.f32();
  m.z = r.f32();
  m.vx = r.f32();
  m.vy = r.f32();
  m.vz = r.f32();
  return m;
}

CommandLong unpack_command_long(const std::vector<uint8_t>& p) {
  Reader r(p);
  CommandLong m;
  for (float& v : m.param) v = r.f32();
  m.command = r.u16();
  m.target_system = r.u8();
  m.target_component = r.u8();
  m.confirmation = r.u8();
  return m;
}

CommandAck unpack_command_ack(const std::vector<uint8_t>& p) {
  Reader r(p);
  CommandAck m;
  m.command = r.u16();
  m.result = r.u8();
  m.progress = r.u8();
  m.result_param2 = r.i32();
  m.target_system = r.u8();
  m.target_component = r.u8();
  return m;
}

SetPositionTargetLocalNed unpack_set_position_target_local_ned(const std::vector<uint8_t>& p) {
  Reader r(p);
  SetPositionTargetLocalNed m;
  m.time_boot_ms = r.u32();
  m.x = r.f32();
  m.y = r.f32();
  m.z = r.f32();
  m.vx = r.f32();
  m.vy = r.f32();
  m.vz = r.f32();
  m.afx = r.f32();
  m.afy = r.f32();
  m.afz = r.f32();
  m.yaw = r.f32();
  m.yaw_rate = r.f32();
  m.type_mask = r.u16();
  m.target_system = r.u8();
  m.target_component = r.u8();
  m.coordinate_frame = r.u8();
  return m;
}

ExtendedSysState unpack_extended_sys_state(const std::vector<uint8_t>& p) {
  Reader r(p);
  ExtendedSysState m;
  m.vtol_state = r.u8();
  m.landed_state = r.u8();
  return m;
}

ParamRequestRead unpack_param_request_read(const std::vector<uint8_t>& p) {
  Reader r(p);
  ParamRequestRead m;
  m.param_index = static_cast<int16_t>(r.u16());
  m.target_system = r.u8();
  m.target_component = r.u8();
  for (char& c : m.param_id) c = static_cast<char>(r.u8());
  return m;
}

ParamValue unpack_param_value(const std::vector<uint8_t>& p) {
  Reader r(p);
  ParamValue m;
  m.param_value = r.f32();
  m.param_count = r.u16();
  m.param_index = r.u16();
  for (char& c : m.param_id) c = static_cast<char>(r.u8());
  m.param_type = r.u8();
  return m;
}

std::string param_name(const char (&id)[16]) {
  size_t n = 0;
  while (n < sizeof id && id[n] != 0) ++n;
  return std::string(id, n);
}

}  // namespace gpilot::mavlink
