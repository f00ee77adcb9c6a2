// The ENGAGE gate of the MAVLink backend: the autopilot's offboard-loss failsafe time (PX4 COM_OF_LOSS_T,
// ArduPilot GUID_TIMEOUT) is read with PARAM_REQUEST_READ and must be known and no longer than
// flight.max_autopilot_loss_s. Times are set by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "mavlink/frame.hpp"
#include "mavlink/messages.hpp"
#include "mavlink/offboard_loss.hpp"
#include "mavlink/session.hpp"

namespace gpilot::mavlink {
namespace {

using A = EngageGate::Action;
constexpr int64_t kS = 1000000;

ParamValue value(const char* name, float v, uint8_t type = kMavParamTypeReal32) {
  ParamValue p;
  std::strncpy(p.param_id, name, sizeof p.param_id);
  p.param_value = v;
  p.param_type = type;
  return p;
}

TEST(OffboardLoss, ParameterPerAutopilot) {
  EXPECT_EQ(offboard_loss_param("px4"), "COM_OF_LOSS_T");
  EXPECT_EQ(offboard_loss_param("ardupilot"), "GUID_TIMEOUT");
}

TEST(OffboardLoss, EngagesOnlyWithinTheLimit) {
  EXPECT_EQ(judge_offboard_loss(value("COM_OF_LOSS_T", 1.0f), 1.0), "");
  EXPECT_EQ(judge_offboard_loss(value("COM_OF_LOSS_T", 0.0f), 1.0), "");  // PX4: failsafe at once
  const std::string too_long = judge_offboard_loss(value("COM_OF_LOSS_T", 3.0f), 1.0);
  EXPECT_NE(too_long.find("COM_OF_LOSS_T is 3.00 s, above flight.max_autopilot_loss_s 1.00 s"), std::string::npos)
      << too_long;
  EXPECT_NE(judge_offboard_loss(value("GUID_TIMEOUT", NAN), 1.0).find("GUID_TIMEOUT is not a time"), std::string::npos);
  EXPECT_NE(judge_offboard_loss(value("GUID_TIMEOUT", -1.0f), 1.0), "");
  EXPECT_NE(judge_offboard_loss(value("GUID_TIMEOUT", 0.5f, 6), 1.0), "");  // INT32: not what we asked for
}

TEST(OffboardLoss, GateAsksResendsAndTimesOut) {
  EngageGate g("COM_OF_LOSS_T", 1.0, 1.0);
  // GIVEN an ENGAGE at t=10 s: a request now, none for a second ENGAGE while it waits
  EXPECT_EQ(g.engage_requested(10 * kS), A::Request);
  EXPECT_EQ(g.engage_requested(10 * kS + 1000), A::None);
  EXPECT_TRUE(g.pending());
  // WHEN no answer: resent every timeout / 4, refused after the timeout
  EXPECT_EQ(g.on_time(10 * kS + 200000), A::None);
  EXPECT_EQ(g.on_time(10 * kS + 250000), A::Request);
  EXPECT_EQ(g.on_time(10 * kS + 400000), A::None);
  EXPECT_EQ(g.on_time(11 * kS), A::Request);
  EXPECT_EQ(g.on_time(11 * kS + 1), A::Refuse);
  EXPECT_FALSE(g.pending());
  EXPECT_NE(g.why().find("did not answer PARAM_REQUEST_READ COM_OF_LOSS_T within 1.00 s"), std::string::npos) << g.why();
  // THEN a late answer changes nothing
  EXPECT_EQ(g.on_param_value(value("COM_OF_LOSS_T", 0.5f)), A::None);
}

TEST(OffboardLoss, GateFollowsTheAnswerToItsOwnParameter) {
  EngageGate g("GUID_TIMEOUT", 1.0, 1.0);
  ASSERT_EQ(g.engage_requested(0), A::Request);
  EXPECT_EQ(g.on_param_value(value("WPNAV_SPEED", 0.5f)), A::None);  // another parameter
  EXPECT_EQ(g.on_param_value(value("GUID_TIMEOUT", 3.0f)), A::Refuse);
  EXPECT_NE(g.why().find("GUID_TIMEOUT is 3.00 s"), std::string::npos);
  ASSERT_EQ(g.engage_requested(5 * kS), A::Request);
  EXPECT_EQ(g.on_param_value(value("GUID_TIMEOUT", 0.75f)), A::Engage);
  EXPECT_EQ(g.last_value(), 0.75);
  // a disengage while waiting drops the ENGAGE
  ASSERT_EQ(g.engage_requested(9 * kS), A::Request);
  g.cancel();
  EXPECT_EQ(g.on_param_value(value("GUID_TIMEOUT", 0.75f)), A::None);
  EXPECT_EQ(g.on_time(20 * kS), A::None);
}

TEST(OffboardLoss, SessionRoundTripOfTheParameterMessages) {
  MavlinkSession s{MavlinkParams{}};
  const auto bytes = s.param_request_read("COM_OF_LOSS_T");
  FrameParser p;
  std::vector<Frame> frames;
  p.feed(bytes.data(), bytes.size(), [&](const Frame& f) { frames.push_back(f); });
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].msgid, ParamRequestRead::kId);
  const ParamRequestRead r = unpack_param_request_read(frames[0].payload);
  EXPECT_EQ(r.param_index, -1);
  EXPECT_EQ(r.target_system, 1);
  EXPECT_EQ(param_name(r.param_id), "COM_OF_LOSS_T");

  // a PARAM_VALUE from the autopilot (system 1) is handed out once
  Frame f;
  f.sysid = 1;
  f.compid = 1;
  f.msgid = ParamValue::kId;
  f.payload = pack(value("COM_OF_LOSS_T", 0.5f));
  const auto in = encode_frame(f);
  s.on_datagram(in.data(), in.size(), 0);
  auto got = s.take_param_values();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(param_name(got[0].param_id), "COM_OF_LOSS_T");
  EXPECT_EQ(got[0].param_value, 0.5f);
  EXPECT_EQ(got[0].param_type, kMavParamTypeReal32);
  EXPECT_TRUE(s.take_param_values().empty());
  char sixteen[16];
  std::memcpy(sixteen, "ABCDEFGHIJKLMNOP", 16);  // 16 characters: no NUL on the wire
  EXPECT_EQ(param_name(sixteen), "ABCDEFGHIJKLMNOP");
}

}  // namespace
}  // namespace gpilot::mavlink
