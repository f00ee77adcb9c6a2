// BusNode on hostile bytes, in-process (memq://, no network): one datagram must never stop a process.
// LCM 1.3.1's generated decoders throw on a string length of 0 or -1 (std::length_error from
// basic_string::_M_replace): caught and rejected with the reason; trailing bytes after a whole message
// are rejected; a handler that throws rejects its message and the node keeps handling the next ones.
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bus_node.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"

using namespace gpilot;

namespace {

std::vector<uint8_t> encode(const flight_control_t& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// The bytes of a FLIGHT_CONTROL whose source string says it is `length` bytes long (LCM: int32 big-endian
// length including the NUL, then the bytes), as an attacker would send it.
std::vector<uint8_t> control_with_string_length(int32_t length) {
  flight_control_t m{};
  m.command = flight_control_t::COMMAND_ENGAGE;
  m.source = "abc";
  std::vector<uint8_t> bytes = encode(m);
  const uint8_t want[8] = {0, 0, 0, 4, 'a', 'b', 'c', 0};
  for (size_t i = 0; i + 8 <= bytes.size(); ++i)
    if (std::memcmp(&bytes[i], want, 8) == 0) {
      const uint32_t u = static_cast<uint32_t>(length);
      bytes[i] = static_cast<uint8_t>(u >> 24), bytes[i + 1] = static_cast<uint8_t>(u >> 16);
      bytes[i + 2] = static_cast<uint8_t>(u >> 8), bytes[i + 3] = static_cast<uint8_t>(u);
      return bytes;
    }
  ADD_FAILURE() << "no string length found in the encoding";
  return bytes;
}

struct BusDecode : ::testing::Test {
  BusNode node{"gpilot-test", "memq://"};
  int controls = 0;
  void SetUp() override {
    node.subscribe<flight_control_t>("FLIGHT_CONTROL", [this](const flight_control_t&, int64_t) { ++controls; });
  }
  void send(const std::vector<uint8_t>& bytes) {
    node.publish_raw("FLIGHT_CONTROL", bytes.data(), bytes.size());
    node.drain();
  }
};

}  // namespace

TEST_F(BusDecode, AStringLengthOfZeroOrMinusOneIsRejectedAndTheNodeKeepsRunning) {
  // (INT32_MIN is left out: the generated decoder computes length - 1 on it, a signed overflow that reads past
  // the datagram; lengths must be checked before the decoder runs: issue 11, not done yet.)
  for (const int32_t length : {0, -1, INT32_MIN + 1, INT32_MAX}) {
    SCOPED_TRACE(length);
    const int64_t before = node.stats().rejected_count();
    send(control_with_string_length(length));
    EXPECT_EQ(node.stats().rejected_count(), before + 1);
    EXPECT_EQ(controls, 0);
  }
  EXPECT_NE(node.stats().last_reject_reason().find("FLIGHT_CONTROL: "), std::string::npos);
  EXPECT_NE(node.stats().last_reject_reason().find("gpilot.flight_control_t"), std::string::npos);
  // THEN a valid request right after is handled
  flight_control_t ok{};
  ok.command = flight_control_t::COMMAND_ENGAGE;
  ok.source = "gpilot-ctl";
  send(encode(ok));
  EXPECT_EQ(controls, 1);
}

TEST_F(BusDecode, TheLengthZeroReasonSaysALengthIsOutOfRange) {
  send(control_with_string_length(0));
  EXPECT_NE(node.stats().last_reject_reason().find("a length field is out of range"), std::string::npos)
      << node.stats().last_reject_reason();
}

TEST_F(BusDecode, TrailingBytesAreNotThisMessage) {
  flight_control_t ok{};
  ok.command = flight_control_t::COMMAND_DISENGAGE;
  ok.source = "gpilot-ctl";
  std::vector<uint8_t> bytes = encode(ok);
  const size_t whole = bytes.size();
  bytes.push_back(0);
  send(bytes);
  EXPECT_EQ(controls, 0);
  EXPECT_EQ(node.stats().last_reject_reason(), "FLIGHT_CONTROL: " + std::to_string(whole + 1) + " bytes hold a gpilot.flight_control_t of " +
                                                   std::to_string(whole) + " bytes and trailing bytes");
}

TEST(BusHandlers, AHandlerThatThrowsRejectsItsMessageAndTheNextOneIsHandled) {
  BusNode node("gpilot-test", "memq://");
  int handled = 0;
  node.subscribe<gesture_cmd_t>("GESTURE_CMD", [&](const gesture_cmd_t& m, int64_t) {
    if (m.seq == 1) throw std::runtime_error("boom");
    ++handled;
  });
  int raw = 0;
  node.subscribe_raw("RAW", [&](const std::string&, const void*, size_t size, int64_t) {
    if (size == 1) throw std::out_of_range("raw boom");
    ++raw;
  });
  gesture_cmd_t cmd{};
  cmd.seq = 1;
  node.publish("GESTURE_CMD", cmd);
  node.drain();
  EXPECT_EQ(node.stats().rejected_count(), 1);
  EXPECT_EQ(node.stats().last_reject_reason(), "GESTURE_CMD: the handler failed on this message: boom");
  cmd.seq = 2;
  node.publish("GESTURE_CMD", cmd);
  node.drain();
  EXPECT_EQ(handled, 1);
  const uint8_t one = 1, two[2] = {1, 2};
  node.publish_raw("RAW", &one, 1);
  node.publish_raw("RAW", two, 2);
  node.drain();
  EXPECT_EQ(raw, 1);
  EXPECT_EQ(node.stats().last_reject_reason(), "RAW: the handler failed on this message: raw boom");
}
