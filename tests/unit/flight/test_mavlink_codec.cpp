// MAVLink v2 codec: the byte-exact vectors of shared STACK.md section 6 (checked there against node-mavlink and
// an independent Python encoder), round trips, and every kind of bad frame rejected and counted.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mavlink/crc.hpp"
#include "mavlink/frame.hpp"
#include "mavlink/hex.hpp"
#include "mavlink/messages.hpp"
#include "mavlink/session.hpp"

namespace gpilot::mavlink {
namespace {

const char* kHeartbeatHex = "fd0900000001010000000400000002035104037bae";
const char* kSetpointHex =
    "fd35000001010154000040e201000000c03f000010c0000020c10000003f00000000000000000000000000000000000000000000a03f0000"
    "0000f80d01010106ab";

std::vector<Frame> parse_all(FrameParser& p, const std::vector<uint8_t>& bytes) {
  std::vector<Frame> out;
  p.feed(bytes.data(), bytes.size(), [&](const Frame& f) { out.push_back(f); });
  return out;
}

TEST(MavlinkCrc, KnownCheckValue) {
  // CRC-16/MCRF4XX check value: "123456789" -> 0x6F91.
  const std::string s = "123456789";
  EXPECT_EQ(crc_x25(reinterpret_cast<const uint8_t*>(s.data()), s.size()), 0x6F91);
}

TEST(MavlinkFrame, HeartbeatMatchesTheReferenceBytes) {
  Heartbeat h;
  h.type = 2;
  h.autopilot = 3;
  h.base_mode = 0x51;
  h.custom_mode = 4;
  h.system_status = 4;
  h.mavlink_version = 3;
  Frame f;
  f.seq = 0;
  f.sysid = 1;
  f.compid = 1;
  f.msgid = Heartbeat::kId;
  f.payload = pack(h);
  EXPECT_EQ(to_hex(encode_frame(f)), kHeartbeatHex);
}

TEST(MavlinkFrame, SetpointMatchesTheReferenceBytes) {
  SetPositionTargetLocalNed m;
  m.time_boot_ms = 123456;
  m.x = 1.5f;
  m.y = -2.25f;
  m.z = -10.0f;
  m.vx = 0.5f;
  m.yaw = 1.25f;
  m.type_mask = 0x0DF8;
  m.target_system = 1;
  m.target_component = 1;
  m.coordinate_frame = 1;
  Frame f;
  f.seq = 1;
  f.sysid = 1;
  f.compid = 1;
  f.msgid = SetPositionTargetLocalNed::kId;
  f.payload = pack(m);
  EXPECT_EQ(to_hex(encode_frame(f)), kSetpointHex);
}

TEST(MavlinkFrame, ParsesTheReferenceBytesFieldByField) {
  FrameParser p;
  const auto frames = parse_all(p, from_hex(std::string(kHeartbeatHex) + kSetpointHex));
  ASSERT_EQ(frames.size(), 2u);
  const Heartbeat h = unpack_heartbeat(frames[0].payload);
  EXPECT_EQ(h.type, 2);
  EXPECT_EQ(h.autopilot, 3);
  EXPECT_EQ(h.base_mode, 0x51);
  EXPECT_EQ(h.custom_mode, 4u);
  EXPECT_EQ(h.system_status, 4);
  EXPECT_EQ(h.mavlink_version, 3);
  EXPECT_EQ(frames[1].seq, 1);
  EXPECT_EQ(frames[1].payload.size(), 53u);  // zero-extended from the 53 sent (nothing truncated here)
  const SetPositionTargetLocalNed m = unpack_set_position_target_local_ned(frames[1].payload);
  EXPECT_EQ(m.time_boot_ms, 123456u);
  EXPECT_EQ(m.x, 1.5f);
  EXPECT_EQ(m.y, -2.25f);
  EXPECT_EQ(m.z, -10.0f);
  EXPECT_EQ(m.vx, 0.5f);
  EXPECT_EQ(m.yaw, 1.25f);
  EXPECT_EQ(m.type_mask, 0x0DF8);
  EXPECT_EQ(m.coordinate_frame, 1);
  EXPECT_EQ(p.counts().frames, 2);
  EXPECT_EQ(p.rejected(), 0);
}

TEST(MavlinkFrame, TrailingZerosAreCutAndRestored) {
  LocalPositionNed m;
  m.time_boot_ms = 5;
  m.x = 1.0f;  // vx..vz zero: 16 trailing zero bytes are not sent
  Frame f;
  f.sysid = 1;
  f.msgid = LocalPositionNed::kId;
  f.payload = pack(m);
  const auto bytes = encode_frame(f);
  EXPECT_EQ(bytes[1], 8);  // time_boot_ms + x
  FrameParser p;
  const auto frames = parse_all(p, bytes);
  ASSERT_EQ(frames.size(), 1u);
  const LocalPositionNed back = unpack_local_position_ned(frames[0].payload);
  EXPECT_EQ(back.x, 1.0f);
  EXPECT_EQ(back.vz, 0.0f);
}

TEST(MavlinkFrame, RoundTripsEveryMessage) {
  CommandLong c;
  c.command = kMavCmdNavTakeoff;
  c.param[6] = 12.5f;
  c.target_system = 1;
  c.confirmation = 2;
  Attitude a;
  a.roll = 0.1f;
  a.yaw = -2.0f;
  a.yawspeed = 0.3f;
  ExtendedSysState e;
  e.landed_state = 2;
  CommandAck k;
  k.command = 400;
  k.result = 4;
  k.result_param2 = -7;
  FrameParser p;
  std::vector<uint8_t> all;
  for (auto bytes : {encode_frame({0, 1, 1, CommandLong::kId, pack(c)}), encode_frame({1, 1, 1, Attitude::kId, pack(a)}),
                     encode_frame({2, 1, 1, ExtendedSysState::kId, pack(e)}),
                     encode_frame({3, 1, 1, CommandAck::kId, pack(k)})})
    all.insert(all.end(), bytes.begin(), bytes.end());
  const auto frames = parse_all(p, all);
  ASSERT_EQ(frames.size(), 4u);
  const CommandLong c2 = unpack_command_long(frames[0].payload);
  EXPECT_EQ(c2.command, kMavCmdNavTakeoff);
  EXPECT_EQ(c2.param[6], 12.5f);
  EXPECT_EQ(c2.confirmation, 2);
  const Attitude a2 = unpack_attitude(frames[1].payload);
  EXPECT_EQ(a2.roll, 0.1f);
  EXPECT_EQ(a2.yaw, -2.0f);
  EXPECT_EQ(a2.yawspeed, 0.3f);
  EXPECT_EQ(unpack_extended_sys_state(frames[2].payload).landed_state, 2);
  const CommandAck k2 = unpack_command_ack(frames[3].payload);
  EXPECT_EQ(k2.command, 400);
  EXPECT_EQ(k2.result, 4);
  EXPECT_EQ(k2.result_param2, -7);
}

TEST(MavlinkFrame, CorruptedBytesAreRejectedAndCounted) {
  // Every single-byte corruption after the magic of a valid frame must not yield that frame unchanged.
  const auto good = from_hex(kSetpointHex);
  int accepted_wrong = 0;
  for (size_t i = 1; i < good.size(); ++i) {
    auto bad = good;
    bad[i] ^= 0x20;
    FrameParser p;
    const auto frames = parse_all(p, bad);
    p.end_of_datagram();
    if (!frames.empty()) ++accepted_wrong;
    EXPECT_GE(p.rejected(), 1) << "byte " << i;
  }
  EXPECT_EQ(accepted_wrong, 0);
}

TEST(MavlinkFrame, BadCrcIsCountedAndTheNextFrameStillParses) {
  auto bytes = from_hex(kHeartbeatHex);
  bytes[12] ^= 0xFF;  // in the payload
  const auto next = from_hex(kSetpointHex);
  bytes.insert(bytes.end(), next.begin(), next.end());
  FrameParser p;
  const auto frames = parse_all(p, bytes);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].msgid, SetPositionTargetLocalNed::kId);
  EXPECT_EQ(p.counts().bad_crc, 1);
}

TEST(MavlinkFrame, WrongLengthUnknownIdSignedAndGarbageAreCounted) {
  FrameParser p;
  // HEARTBEAT claiming 10 payload bytes (it has 9)
  auto too_long = from_hex(kHeartbeatHex);
  too_long[1] = 10;
  parse_all(p, too_long);
  p.end_of_datagram();
  EXPECT_EQ(p.counts().bad_length, 1);
  // an id we do not know (SYS_STATUS = 1): skipped whole, counted once
  auto unknown = from_hex(kHeartbeatHex);
  unknown[7] = 1;
  EXPECT_TRUE(parse_all(p, unknown).empty());
  EXPECT_EQ(p.counts().unknown_id, 1);
  // a signed frame: 13 signature bytes after the CRC, flag 0x01
  auto sig = from_hex(kHeartbeatHex);
  sig[2] = kIncompatSigned;
  const uint16_t crc = crc_accumulate(50, crc_x25(sig.data() + 1, sig.size() - 3));
  sig[sig.size() - 2] = static_cast<uint8_t>(crc);
  sig[sig.size() - 1] = static_cast<uint8_t>(crc >> 8);
  sig.insert(sig.end(), 13, 0xAA);
  EXPECT_TRUE(parse_all(p, sig).empty());
  EXPECT_EQ(p.counts().unsupported, 1);
  // garbage before a good frame is skipped; a datagram that ends inside a frame is truncated
  const int64_t skipped_before = p.counts().skipped_bytes;
  auto g = from_hex("0102fe03" + std::string(kHeartbeatHex));
  EXPECT_EQ(parse_all(p, g).size(), 1u);
  EXPECT_EQ(p.counts().skipped_bytes - skipped_before, 4);
  auto cut = from_hex(kSetpointHex);
  cut.resize(30);
  EXPECT_TRUE(parse_all(p, cut).empty());
  p.end_of_datagram();
  EXPECT_EQ(p.counts().truncated, 1);
  EXPECT_EQ(p.counts().frames, 1);
}

TEST(MavlinkSession, SetpointIsBodyNedVelocityAndYawRateOnly) {
  MavlinkParams mp;
  MavlinkSession s(mp);
  Setpoint sp;
  sp.velocity[0] = 0.25;
  sp.velocity[1] = -0.5;
  sp.velocity[2] = -0.125;
  sp.yaw_rate = 0.3;
  s.setpoint(sp, 1000000);  // first frame sets boot time
  const auto bytes = s.setpoint(sp, 3500000);
  FrameParser p;
  const auto frames = parse_all(p, bytes);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].seq, 1);
  EXPECT_EQ(frames[0].sysid, 255);
  EXPECT_EQ(frames[0].compid, 191);
  const auto m = unpack_set_position_target_local_ned(frames[0].payload);
  EXPECT_EQ(m.time_boot_ms, 2500u);
  EXPECT_EQ(m.coordinate_frame, 8);  // MAV_FRAME_BODY_NED
  EXPECT_EQ(m.type_mask, 1479);      // 0b0000010111000111: ignore position, acceleration, yaw
  EXPECT_EQ(m.vx, 0.25f);
  EXPECT_EQ(m.vy, -0.5f);
  EXPECT_EQ(m.vz, -0.125f);
  EXPECT_EQ(m.yaw_rate, 0.3f);
  EXPECT_EQ(m.target_system, 1);
  EXPECT_EQ(m.target_component, 1);
}

TEST(MavlinkSession, AutopilotMessagesBecomeVehicleState) {
  MavlinkSession s{MavlinkParams{}};
  Heartbeat h;
  h.autopilot = 12;  // PX4
  h.type = 2;
  h.base_mode = kMavModeFlagSafetyArmed | 1;
  Attitude a;
  a.roll = 0.05f;
  a.pitch = -0.1f;
  a.yaw = 1.5f;
  a.yawspeed = 0.2f;
  ExtendedSysState e;
  e.landed_state = 2;
  LocalPositionNed l;
  l.x = 3;
  l.y = -4;
  l.z = -2;
  l.vx = 0.5f;
  std::vector<uint8_t> d;
  for (auto b : {encode_frame({0, 1, 1, Heartbeat::kId, pack(h)}), encode_frame({1, 1, 1, Attitude::kId, pack(a)}),
                 encode_frame({2, 1, 1, ExtendedSysState::kId, pack(e)}),
                 encode_frame({3, 1, 1, LocalPositionNed::kId, pack(l)})})
    d.insert(d.end(), b.begin(), b.end());
  const auto st = s.on_datagram(d.data(), d.size(), 777);
  ASSERT_TRUE(st.has_value());
  EXPECT_EQ(st->utime, 777);
  EXPECT_TRUE(st->armed);
  EXPECT_EQ(st->landed, VehicleState::Landed::InAir);
  EXPECT_EQ(st->position[0], 3);
  EXPECT_EQ(st->position[1], -4);
  EXPECT_EQ(st->position[2], -2);
  EXPECT_EQ(st->velocity[0], 0.5);
  EXPECT_FLOAT_EQ(st->attitude[2], 1.5f);
  EXPECT_FLOAT_EQ(st->yaw_rate, 0.2f);
  EXPECT_TRUE(s.heard_autopilot());
  // another system's position is not ours
  const auto other = encode_frame({4, 2, 1, LocalPositionNed::kId, pack(l)});
  EXPECT_FALSE(s.on_datagram(other.data(), other.size(), 778).has_value());
  EXPECT_EQ(s.other_system(), 1);
}

TEST(MavlinkSession, CommandsCarryTheirMavCmd) {
  MavlinkSession s{MavlinkParams{}};
  FrameParser p;
  auto one = [&](const std::vector<uint8_t>& b) {
    const auto f = parse_all(p, b);
    EXPECT_EQ(f.size(), 1u);
    return unpack_command_long(f.at(0).payload);
  };
  EXPECT_EQ(one(s.arm(true)).command, 400);
  EXPECT_EQ(one(s.arm(true)).param[0], 1.0f);
  EXPECT_EQ(one(s.arm(false)).param[0], 0.0f);
  const CommandLong t = one(s.takeoff(3.0f));
  EXPECT_EQ(t.command, 22);
  EXPECT_TRUE(std::isnan(t.param[6]));  // PX4 reads param7 as AMSL: its own take-off altitude instead
  EXPECT_EQ(one(s.land()).command, 21);
  const CommandLong m = one(s.engage_mode());
  EXPECT_EQ(m.command, 176);
  EXPECT_EQ(m.param[0], 1.0f);
  EXPECT_EQ(m.param[1], 6.0f);  // PX4 main mode OFFBOARD
  MavlinkParams ap;
  ap.autopilot = "ardupilot";
  MavlinkSession a(ap);
  EXPECT_EQ(one(a.takeoff(3.0f)).param[6], 3.0f);  // ArduPilot: metres above home
  EXPECT_EQ(one(a.engage_mode()).param[1], 4.0f);  // Copter GUIDED
}

TEST(MavlinkEndpoint, ParsesUdpHostPortAndRejectsTheRest) {
  const Endpoint e = parse_endpoint("udp:127.0.0.1:14580");
  EXPECT_EQ(e.host, "127.0.0.1");
  EXPECT_EQ(e.port, 14580);
  for (const char* bad : {"tcp:127.0.0.1:5760", "udp:127.0.0.1", "udp::14580", "udp:h:0", "udp:h:70000", "udp:h:1x"})
    EXPECT_THROW(parse_endpoint(bad), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace gpilot::mavlink
