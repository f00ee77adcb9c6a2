// The proof that an autopilot reads us right: the bytes gpilot-flight sends are decoded by node-mavlink (an
// independent implementation, tests/mavlink/peer.js) field by field, and bytes node-mavlink encodes are decoded
// by ours. No network: the peer reads stdin and writes stdout.
#include <gtest/gtest.h>
#include <array>
#include <chrono>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "flight_bridge.hpp"
#include "mavlink/frame.hpp"
#include "mavlink/hex.hpp"
#include "mavlink/messages.hpp"
#include "mavlink/session.hpp"

namespace gpilot::mavlink {
namespace {

const std::string kPeerDir = GPILOT_MAVLINK_PEER_DIR;

bool peer_available(std::string& why) {
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    why = "node is not installed (deploy/setup installs nodejs)";
    return false;
  }
  if (access((kPeerDir + "/node_modules/node-mavlink/package.json").c_str(), R_OK) != 0) {
    why = "node-mavlink is not installed in tests/mavlink (run deploy/setup, or npm ci there)";
    return false;
  }
  return true;
}

#define REQUIRE_PEER()                                  \
  do {                                                  \
    std::string why;                                    \
    if (!peer_available(why)) GTEST_SKIP() << why;      \
  } while (0)

// Runs `node peer.js args` with `input` on stdin; returns stdout lines.
std::vector<std::string> run_peer(const std::string& args, const std::string& input) {
  char path[] = "/tmp/gpilot-mavlink-peer-XXXXXX";
  const int fd = mkstemp(path);
  EXPECT_GE(fd, 0);
  close(fd);
  std::ofstream(path) << input;
  const std::string cmd = "cd '" + kPeerDir + "' && node peer.js " + args + " < '" + path + "'";
  std::vector<std::string> lines;
  FILE* p = popen(cmd.c_str(), "r");
  EXPECT_NE(p, nullptr);
  std::string cur;
  for (int c; (c = fgetc(p)) != EOF;) {
    if (c == '\n') {
      lines.push_back(cur);
      cur.clear();
    } else {
      cur += static_cast<char>(c);
    }
  }
  EXPECT_EQ(pclose(p), 0) << cmd;
  unlink(path);
  return lines;
}

// The value text of "key": in one JSON line (numbers and short strings; enough for the peer's flat output).
std::string field(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\":";
  const size_t at = json.find(k);
  if (at == std::string::npos) return "<missing " + key + ">";
  const size_t start = at + k.size();
  size_t end = start;
  if (json[start] == '"') end = json.find('"', start + 1) + 1;
  else
    while (end < json.size() && json[end] != ',' && json[end] != '}') ++end;
  return json.substr(start, end - start);
}

double num(const std::string& json, const std::string& key) { return std::stod(field(json, key)); }

TEST(NodeMavlink, ItsRegistryAgreesWithOurIdsCrcExtrasAndLengths) {
  REQUIRE_PEER();
  const uint32_t ids[] = {0, 20, 22, 30, 32, 76, 77, 84, 245};
  std::string args = "table";
  for (uint32_t id : ids) args += " " + std::to_string(id);
  const auto out = run_peer(args, "");
  ASSERT_EQ(out.size(), 1u);
  for (uint32_t id : ids) {
    const MessageInfo* info = message_info(id);
    ASSERT_NE(info, nullptr);
    const std::string entry = out[0].substr(out[0].find("\"" + std::to_string(id) + "\":"));
    EXPECT_EQ(field(entry, "name"), "\"" + std::string(info->name) + "\"") << id;
    EXPECT_EQ(num(entry, "crcExtra"), info->crc_extra) << info->name;
    EXPECT_EQ(num(entry, "length"), info->length) << info->name;
  }
}

TEST(NodeMavlink, DecodesEveryFrameWeSendFieldByField) {
  REQUIRE_PEER();
  // GIVEN a setpoint from the bridge for a user pointing to their right (image left): body -y at 0.5 m/s
  FlightBridge bridge{FlightParams{}};
  BridgeInputs in;
  in.now = in.command_received = in.track_received = in.vehicle_received = 1700000000000000;
  GestureCommand c;
  c.seq = 5;
  c.track_id = 1;
  c.mode = GestureMode::Fine;
  c.direction[0] = -0.5;
  c.direction[1] = 0.25;
  c.user_box_width = 100;
  in.command = c;
  UserTrack t;
  t.tracking = true;
  t.track_id = 1;
  t.image_width = 640;
  t.box[0] = 0.625 * 640 - 50;  // user right of centre by 1/8 of the width: yaw rate 2 * 0.125 = 0.25 rad/s
  t.box[2] = 100;
  t.box[3] = 300;
  in.track = t;
  in.vehicle = VehicleState{};
  in.vehicle->position[2] = -1.5;  // in the air, inside the height band
  in.engaged = true;
  const Setpoint sp = bridge.update(in);
  ASSERT_EQ(sp.reasons, 0);

  MavlinkSession s{MavlinkParams{}};
  std::string input;
  input += to_hex(s.heartbeat()) + "\n";
  s.setpoint(sp, 1000000);
  input += to_hex(s.setpoint(sp, 1250000)) + "\n";
  input += to_hex(s.arm(true)) + "\n";
  input += to_hex(s.takeoff(2.5f)) + "\n";
  input += to_hex(s.land()) + "\n";
  input += to_hex(s.engage_mode()) + "\n";
  MavlinkParams ardupilot;
  ardupilot.autopilot = "ardupilot";
  input += to_hex(MavlinkSession(ardupilot).takeoff(2.5f)) + "\n";
  input += to_hex(s.param_request_read("COM_OF_LOSS_T")) + "\n";
  const auto out = run_peer("decode", input);
  ASSERT_EQ(out.size(), 9u);  // 8 packets + summary

  const std::string& hb = out[0];
  EXPECT_EQ(field(hb, "msg"), "\"HEARTBEAT\"");
  EXPECT_EQ(num(hb, "v"), 2);
  EXPECT_EQ(num(hb, "seq"), 0);
  EXPECT_EQ(num(hb, "sysid"), 255);
  EXPECT_EQ(num(hb, "compid"), 191);
  EXPECT_EQ(num(hb, "type"), kMavTypeOnboardController);
  EXPECT_EQ(num(hb, "autopilot"), kMavAutopilotInvalid);
  EXPECT_EQ(num(hb, "baseMode"), 0);
  EXPECT_EQ(num(hb, "customMode"), 0);
  EXPECT_EQ(num(hb, "systemStatus"), kMavStateActive);
  EXPECT_EQ(num(hb, "mavlinkVersion"), 3);

  const std::string& st = out[1];
  EXPECT_EQ(field(st, "msg"), "\"SET_POSITION_TARGET_LOCAL_NED\"");
  EXPECT_EQ(num(st, "seq"), 2);
  EXPECT_EQ(num(st, "timeBootMs"), 250);
  EXPECT_EQ(num(st, "coordinateFrame"), 8);  // MAV_FRAME_BODY_NED
  EXPECT_EQ(num(st, "typeMask"), 1479);      // velocity and yaw rate only
  EXPECT_EQ(num(st, "targetSystem"), 1);
  EXPECT_EQ(num(st, "targetComponent"), 1);
  EXPECT_EQ(num(st, "vx"), 0.0);
  EXPECT_EQ(num(st, "vy"), -0.5);   // body left: the user's right
  EXPECT_EQ(num(st, "vz"), 0.25);   // hand below the shoulder: down
  EXPECT_EQ(num(st, "yawRate"), 0.25);
  for (const char* k : {"x", "y", "z", "afx", "afy", "afz", "yaw"}) EXPECT_EQ(num(st, k), 0.0) << k;

  const std::string& arm = out[2];
  EXPECT_EQ(field(arm, "msg"), "\"COMMAND_LONG\"");
  EXPECT_EQ(num(arm, "command"), 400);
  EXPECT_EQ(num(arm, "param1"), 1);
  EXPECT_EQ(num(arm, "targetSystem"), 1);
  EXPECT_EQ(num(arm, "targetComponent"), 1);
  EXPECT_EQ(num(arm, "confirmation"), 0);
  EXPECT_EQ(num(out[3], "command"), 22);
  EXPECT_EQ(field(out[3], "param7"), "null");  // PX4: its own take-off altitude (param7 would be AMSL)
  EXPECT_EQ(field(out[3], "param4"), "null");  // NaN: the autopilot's default yaw (JSON has no NaN)
  EXPECT_EQ(num(out[4], "command"), 21);
  EXPECT_EQ(num(out[5], "command"), 176);
  EXPECT_EQ(num(out[5], "param1"), 1);
  EXPECT_EQ(num(out[5], "param2"), 6);

  EXPECT_NE(out.back().find("\"summary\""), std::string::npos);
  EXPECT_EQ(num(out[6], "command"), 22);
  EXPECT_EQ(num(out[6], "param7"), 2.5);  // ArduPilot: metres above home
  EXPECT_EQ(field(out[7], "msg"), "\"PARAM_REQUEST_READ\"");
  EXPECT_EQ(field(out[7], "paramId"), "\"COM_OF_LOSS_T\"");
  EXPECT_EQ(num(out[7], "paramIndex"), -1);
  EXPECT_EQ(num(out[7], "targetSystem"), 1);
  EXPECT_EQ(num(out[7], "targetComponent"), 1);
  EXPECT_EQ(num(out.back(), "valid"), 8);
  EXPECT_EQ(num(out.back(), "invalid"), 0);
}

TEST(NodeMavlink, RejectsOurFrameWithACorruptedByteAsWeDo) {
  REQUIRE_PEER();
  MavlinkSession s{MavlinkParams{}};
  Setpoint sp;
  sp.velocity[1] = -0.5;
  auto bytes = s.setpoint(sp, 0);
  bytes[20] ^= 0x01;
  const auto out = run_peer("decode", to_hex(bytes) + "\n");
  ASSERT_EQ(out.size(), 1u);  // the summary only: no packet
  EXPECT_EQ(num(out[0], "valid"), 0);
  EXPECT_EQ(num(out[0], "crcErrors"), 1);
  FrameParser p;
  int frames = 0;
  p.feed(bytes.data(), bytes.size(), [&](const Frame&) { ++frames; });
  EXPECT_EQ(frames, 0);
  EXPECT_EQ(p.counts().bad_crc, 1);
}

TEST(NodeMavlink, WeDecodeWhatItEncodes) {
  REQUIRE_PEER();
  const std::string req =
      R"({"msg":"HEARTBEAT","seq":10,"sysid":1,"compid":1,"fields":{"type":2,"autopilot":12,"baseMode":209,"customMode":393216,"systemStatus":4,"mavlinkVersion":3}})"
      "\n"
      R"({"msg":"ATTITUDE","seq":11,"sysid":1,"compid":1,"fields":{"timeBootMs":5000,"roll":0.125,"pitch":-0.0625,"yaw":-1.5,"rollspeed":0.5,"pitchspeed":0.25,"yawspeed":-0.375}})"
      "\n"
      R"({"msg":"EXTENDED_SYS_STATE","seq":12,"sysid":1,"compid":1,"fields":{"vtolState":0,"landedState":2}})"
      "\n"
      R"({"msg":"COMMAND_ACK","seq":13,"sysid":1,"compid":1,"fields":{"command":400,"result":0,"targetSystem":255,"targetComponent":191}})"
      "\n"
      R"({"msg":"LOCAL_POSITION_NED","seq":14,"sysid":1,"compid":1,"fields":{"timeBootMs":5010,"x":3.5,"y":-1.25,"z":-2.0,"vx":0.5,"vy":-0.25,"vz":0.125}})"
      "\n"
      R"({"msg":"PARAM_VALUE","seq":15,"sysid":1,"compid":1,"fields":{"paramId":"COM_OF_LOSS_T","paramValue":0.75,"paramType":9,"paramCount":900,"paramIndex":123}})"
      "\n";
  const auto out = run_peer("encode", req);
  ASSERT_EQ(out.size(), 6u);
  std::vector<uint8_t> datagram;
  for (const auto& line : out) {
    const auto b = from_hex(line);
    datagram.insert(datagram.end(), b.begin(), b.end());
  }
  MavlinkSession s{MavlinkParams{}};
  const auto state = s.on_datagram(datagram.data(), datagram.size(), 4242);
  EXPECT_EQ(s.parser().counts().frames, 6);
  const auto params = s.take_param_values();
  ASSERT_EQ(params.size(), 1u);
  EXPECT_EQ(param_name(params[0].param_id), "COM_OF_LOSS_T");
  EXPECT_EQ(params[0].param_value, 0.75f);
  EXPECT_EQ(params[0].param_type, kMavParamTypeReal32);
  EXPECT_EQ(params[0].param_count, 900);
  EXPECT_EQ(params[0].param_index, 123);
  EXPECT_EQ(s.parser().rejected(), 0);
  ASSERT_TRUE(state.has_value());
  EXPECT_EQ(state->utime, 4242);
  EXPECT_TRUE(state->armed);  // baseMode 209 has the armed bit (128)
  EXPECT_EQ(state->landed, VehicleState::Landed::InAir);
  EXPECT_EQ(state->position[0], 3.5);
  EXPECT_EQ(state->position[1], -1.25);
  EXPECT_EQ(state->position[2], -2.0);
  EXPECT_EQ(state->velocity[0], 0.5);
  EXPECT_EQ(state->velocity[1], -0.25);
  EXPECT_EQ(state->velocity[2], 0.125);
  EXPECT_EQ(state->attitude[0], 0.125);
  EXPECT_EQ(state->attitude[1], -0.0625);
  EXPECT_EQ(state->attitude[2], -1.5);
  EXPECT_EQ(state->yaw_rate, -0.375);
  ASSERT_TRUE(s.last_ack().has_value());
  EXPECT_EQ(s.last_ack()->command, 400);
  EXPECT_EQ(s.last_ack()->target_system, 255);
  EXPECT_EQ(s.last_ack()->target_component, 191);
  // and the raw frames agree field by field with what was asked
  FrameParser p;
  std::vector<Frame> frames;
  p.feed(datagram.data(), datagram.size(), [&](const Frame& f) { frames.push_back(f); });
  ASSERT_EQ(frames.size(), 6u);
  const Heartbeat h = unpack_heartbeat(frames[0].payload);
  EXPECT_EQ(frames[0].seq, 10);
  EXPECT_EQ(h.custom_mode, 393216u);
  EXPECT_EQ(h.autopilot, 12);
  EXPECT_EQ(h.type, 2);
  const Attitude a = unpack_attitude(frames[1].payload);
  EXPECT_EQ(a.time_boot_ms, 5000u);
  EXPECT_EQ(a.rollspeed, 0.5f);
  EXPECT_EQ(a.pitchspeed, 0.25f);
  EXPECT_EQ(unpack_local_position_ned(frames[4].payload).time_boot_ms, 5010u);
}


// MAVLink 2 signing, both directions, against node-mavlink's own signing: our signed frames verify with
// the key and not with another; its signed frames pass our check with the key, and a wrong key, a missing
// signature, a replayed frame and a frame signed two minutes ago are each rejected and counted.
std::array<uint8_t, 32> key_of(uint8_t fill) {
  std::array<uint8_t, 32> k;
  for (size_t i = 0; i < k.size(); ++i) k[i] = static_cast<uint8_t>(fill + 7 * i);
  return k;
}

std::string hex_of(const std::array<uint8_t, 32>& k) { return to_hex(std::vector<uint8_t>(k.begin(), k.end())); }

int64_t now_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

TEST(NodeMavlink, ChecksOurSignaturesWithTheKeyOnly) {
  REQUIRE_PEER();
  MavlinkSession s{MavlinkParams{}};
  s.enable_signing(key_of(1), 7);
  s.set_time(now_utime());
  Setpoint sp;
  sp.velocity[0] = 0.5;
  const auto hb = s.heartbeat();
  const auto set = s.setpoint(sp, now_utime());
  ASSERT_EQ(hb[2] & kIncompatSigned, kIncompatSigned);
  const std::string input = to_hex(hb) + "\n" + to_hex(set) + "\n";
  const auto good = run_peer("decode " + hex_of(key_of(1)), input);
  ASSERT_EQ(good.size(), 3u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(field(good[i], "signed"), "true") << good[i];
    EXPECT_EQ(field(good[i], "signatureValid"), "true") << good[i];
  }
  EXPECT_EQ(field(good[1], "msg"), "\"SET_POSITION_TARGET_LOCAL_NED\"");
  EXPECT_EQ(num(good[2], "crcErrors"), 0);
  const auto wrong = run_peer("decode " + hex_of(key_of(2)), input);
  ASSERT_EQ(wrong.size(), 3u);
  EXPECT_EQ(field(wrong[0], "signatureValid"), "false");
  EXPECT_EQ(field(wrong[1], "signatureValid"), "false");
}

TEST(NodeMavlink, WeReadItsSignedFramesWithTheKeyAndRefuseTheRest) {
  REQUIRE_PEER();
  const int64_t now = now_utime();
  auto request = [&](int seq, int64_t ms, const std::string& key) {
    return R"({"msg":"LOCAL_POSITION_NED","seq":)" + std::to_string(seq) +
           R"(,"sysid":1,"compid":1,"fields":{"timeBootMs":5010,"x":3.5,"y":-1.25,"z":-2.0},"sign":{"key":")" + key +
           R"(","linkId":3,"timestamp":)" + std::to_string(ms) + "}}\n";
  };
  const std::string key = hex_of(key_of(1));
  const auto out = run_peer("encode", request(1, now / 1000, key) + request(2, now / 1000 + 1, key) +
                                          request(3, now / 1000 - 120000, key) +
                                          R"({"msg":"LOCAL_POSITION_NED","seq":4,"sysid":1,"compid":1,"fields":{"x":1}})" "\n");
  ASSERT_EQ(out.size(), 4u);
  const auto first = from_hex(out[0]), second = from_hex(out[1]), old = from_hex(out[2]), unsigned_frame = from_hex(out[3]);

  // with the key: read; the same frame again is a replay; a signature two minutes old on a new link is refused
  MavlinkSession s{MavlinkParams{}};
  s.enable_signing(key_of(1), 7);
  ASSERT_TRUE(s.on_datagram(first.data(), first.size(), now).has_value());
  EXPECT_FALSE(s.on_datagram(first.data(), first.size(), now).has_value());
  EXPECT_STREQ(s.parser().last_reject(), "replayed signed frame (its timestamp is not after the link's last)");
  ASSERT_TRUE(s.on_datagram(second.data(), second.size(), now).has_value());
  EXPECT_FALSE(s.on_datagram(unsigned_frame.data(), unsigned_frame.size(), now).has_value());
  EXPECT_EQ(s.parser().counts().unsigned_frames, 1);
  MavlinkSession fresh{MavlinkParams{}};
  fresh.enable_signing(key_of(1), 7);
  EXPECT_FALSE(fresh.on_datagram(old.data(), old.size(), now).has_value());
  EXPECT_STREQ(fresh.parser().last_reject(), "signed frame more than a minute old on a new link (a replay)");
  EXPECT_EQ(s.parser().counts().frames, 2);
  EXPECT_EQ(s.parser().counts().bad_signature, 1);

  // with another key: nothing is read
  MavlinkSession other{MavlinkParams{}};
  other.enable_signing(key_of(2), 7);
  EXPECT_FALSE(other.on_datagram(first.data(), first.size(), now).has_value());
  EXPECT_STREQ(other.parser().last_reject(), "bad signature (wrong key or altered)");
  // without a key (signing off): signed frames cannot be checked, so they are not read
  MavlinkSession none{MavlinkParams{}};
  EXPECT_FALSE(none.on_datagram(first.data(), first.size(), now).has_value());
  EXPECT_EQ(none.parser().counts().unsupported, 1);
}

}  // namespace
}  // namespace gpilot::mavlink
