// BusNode on hostile bytes, in-process (memq://, no network): one datagram must never stop a process.
// LCM 1.3.1's generated decoders throw on a string length of 0 or -1 (std::length_error from
// basic_string::_M_replace): caught and rejected with the reason; trailing bytes after a whole message
// are rejected; a handler that refuses its message (InputError) rejects it, a handler that fails otherwise
// (a defect) is logged and puts the process in ERROR; either way the node keeps handling the next ones.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "bus_node.hpp"
#include "gpilot/autopilot_t.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "wire_lengths.hpp"

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
  // (INT32_MIN: LCM's decoder alone computes length - 1, overflows and reads ~2 GB past the datagram: a
  // segfault. check_wire_lengths stops it before the decoder runs.)
  for (const int32_t length : {0, -1, INT32_MIN, INT32_MIN + 1, INT32_MAX, 5}) {
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

TEST_F(BusDecode, TheReasonNamesTheLength) {
  const auto bytes = control_with_string_length(0);
  send(bytes);
  EXPECT_EQ(node.stats().last_reject_reason(), "FLIGHT_CONTROL: " + std::to_string(bytes.size()) +
                                                   " bytes do not decode as gpilot.flight_control_t: a string length of 0 with 4 bytes left");
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
  EXPECT_EQ(node.stats().last_reject_reason(), "FLIGHT_CONTROL: " + std::to_string(whole + 1) +
                                                   " bytes do not decode as gpilot.flight_control_t: 1 bytes after the message");
  // AND for a type of fixed size, the decoder's own count says so
  gesture_cmd_t cmd{};
  std::vector<uint8_t> c(static_cast<size_t>(cmd.getEncodedSize()) + 2);
  cmd.encode(c.data(), 0, static_cast<int>(c.size()) - 2);
  int commands = 0;
  node.subscribe<gesture_cmd_t>("GESTURE_CMD", [&](const gesture_cmd_t&, int64_t) { ++commands; });
  node.publish_raw("GESTURE_CMD", c.data(), c.size());
  node.drain();
  EXPECT_EQ(commands, 0);
  EXPECT_EQ(node.stats().last_reject_reason(), "GESTURE_CMD: " + std::to_string(c.size()) + " bytes hold a gpilot.gesture_cmd_t of " +
                                                   std::to_string(c.size() - 2) + " bytes and trailing bytes");
}

TEST(BusHandlers, AHandlerThatRefusesItsInputRejectsItAndTheNextOneIsHandled) {
  // GIVEN a typed and a raw handler that refuse some messages with an InputError (the message's fault)
  BusNode node("gpilot-test", "memq://");
  int handled = 0;
  node.subscribe<gesture_cmd_t>("GESTURE_CMD", [&](const gesture_cmd_t& m, int64_t) {
    if (m.seq == 1) throw InputError("seq 1 is not usable");
    ++handled;
  });
  int raw = 0;
  node.subscribe_raw("RAW", [&](const std::string&, const void*, size_t size, int64_t) {
    if (size == 1) throw InputError("one byte is not a record");
    ++raw;
  });
  node.set_state(health_t::STATE_OK, "running");
  // WHEN one message of each is refused and the next one is not
  gesture_cmd_t cmd{};
  cmd.seq = 1;
  node.publish("GESTURE_CMD", cmd);
  node.drain();
  // THEN the refused one is a counted rejection with its reason
  EXPECT_EQ(node.stats().rejected_count(), 1);
  EXPECT_EQ(node.stats().last_reject_reason(), "GESTURE_CMD: seq 1 is not usable");
  cmd.seq = 2;
  node.publish("GESTURE_CMD", cmd);
  node.drain();
  EXPECT_EQ(handled, 1);
  const uint8_t one = 1, two[2] = {1, 2};
  node.publish_raw("RAW", &one, 1);
  node.publish_raw("RAW", two, 2);
  node.drain();
  EXPECT_EQ(raw, 1);
  EXPECT_EQ(node.stats().rejected_count(), 2);
  EXPECT_EQ(node.stats().last_reject_reason(), "RAW: one byte is not a record");
  // AND the process is not at fault: no failure, HEALTH keeps the stage's state
  EXPECT_EQ(node.stats().failure_count(), 0);
  const health_t h = node.stats().report(1'000'000, "gpilot-test", 1);
  EXPECT_EQ(h.state, health_t::STATE_OK);
  EXPECT_EQ(h.state_detail, "running");
}

TEST(BusHandlers, AHandlerThatFailsIsLoggedAndPutsTheProcessInError) {
  // GIVEN handlers with defects: a logic error, an OpenCV assertion, an allocation failure, a raw handler's
  BusNode node("gpilot-test", "memq://");
  int handled = 0;
  node.subscribe<gesture_cmd_t>("GESTURE_CMD", [&](const gesture_cmd_t& m, int64_t) {
    if (m.seq == 1) throw std::logic_error("Dsst::restore before init");
    if (m.seq == 2) throw cv::Exception(cv::Error::StsAssert, "a.size == b.size", "f", "file.cpp", 1);
    if (m.seq == 3) throw std::bad_alloc();
    ++handled;
  });
  node.subscribe_raw("RAW", [&](const std::string&, const void*, size_t, int64_t) {
    throw std::out_of_range("vector::at");  // a std::logic_error too
  });
  node.set_state(health_t::STATE_OK, "running");
  // WHEN each fails on its message, and a good message follows
  ::testing::internal::CaptureStderr();
  for (int64_t seq = 1; seq <= 4; ++seq) {
    gesture_cmd_t cmd{};
    cmd.seq = seq;
    node.publish("GESTURE_CMD", cmd);
    node.drain();
  }
  const uint8_t one = 1;
  node.publish_raw("RAW", &one, 1);
  node.drain();
  const std::string log = ::testing::internal::GetCapturedStderr();
  // THEN the process keeps handling messages, and none of the failures is counted as a bad message
  EXPECT_EQ(handled, 1);
  EXPECT_EQ(node.stats().rejected_count(), 0);
  EXPECT_EQ(node.stats().failure_count(), 4);
  // AND each failure (the 1st, 2nd, 4th: the log is thinned) is logged at error level with what was thrown
  EXPECT_NE(log.find(": error: the handler of GESTURE_CMD failed (1 so far): Dsst::restore before init"), std::string::npos) << log;
  EXPECT_NE(log.find("(2 so far)"), std::string::npos) << log;
  EXPECT_NE(log.find("a.size == b.size"), std::string::npos) << log;
  EXPECT_EQ(log.find("(3 so far)"), std::string::npos) << log;
  EXPECT_NE(log.find(": error: the handler of RAW failed (4 so far): vector::at"), std::string::npos) << log;
  // AND HEALTH says ERROR with the last failure, even after the stage sets its state again
  node.set_state(health_t::STATE_OK, "tracking");
  const health_t h = node.stats().report(1'000'000, "gpilot-test", 1);
  EXPECT_EQ(h.state, health_t::STATE_ERROR);
  EXPECT_EQ(h.state_detail, "4 failures of this process, the last: RAW: vector::at; tracking");
  // AND a process on its way out says so
  node.set_state(health_t::STATE_STOPPING, "stopping");
  EXPECT_EQ(node.stats().report(2'000'000, "gpilot-test", 1).state, health_t::STATE_STOPPING);
}

namespace {

template <class Msg>
std::vector<uint8_t> encoded(const Msg& m) {
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace

TEST(WireLengths, EachLayoutWalksItsTypesEncodingExactly) {
  // GIVEN messages with strings and data of lengths that differ from each other
  flight_control_t c{};
  c.source = "gpilot-ctl";
  tracker_init_t t{};
  t.source = "a test";
  health_t h{};
  h.name = "gpilot-hands";
  h.state_detail = "skin model data/skin/skin_model.yaml";
  h.last_reject_reason = "x";
  image_t im{};
  im.size = 7;
  im.data.assign(7, 9);
  config_t cf{};
  cf.process = "gpilot-decide";
  cf.yaml = "decide:\n  lambda4: 0.25\n";
  autopilot_t ap{};
  ap.kind = autopilot_t::KIND_PARAM_VALUE;
  ap.param_id = "COM_OF_LOSS_T";
  // THEN each layout ends exactly at the end of its encoding, and one byte less is noticed
  EXPECT_EQ(check_wire_lengths<flight_control_t>(encoded(c).data(), encoded(c).size()), "");
  EXPECT_EQ(check_wire_lengths<tracker_init_t>(encoded(t).data(), encoded(t).size()), "");
  EXPECT_EQ(check_wire_lengths<health_t>(encoded(h).data(), encoded(h).size()), "");
  EXPECT_EQ(check_wire_lengths<image_t>(encoded(im).data(), encoded(im).size()), "");
  EXPECT_EQ(check_wire_lengths<config_t>(encoded(cf).data(), encoded(cf).size()), "");
  EXPECT_EQ(check_wire_lengths<autopilot_t>(encoded(ap).data(), encoded(ap).size()), "");
  const auto ab = encoded(ap);
  EXPECT_EQ(check_wire_lengths<autopilot_t>(ab.data(), ab.size() - 1), "truncated");
  const auto hb = encoded(h);
  EXPECT_EQ(check_wire_lengths<health_t>(hb.data(), hb.size() - 1), "truncated");
  // AND a type without strings or arrays has no layout to check
  EXPECT_TRUE(wire_layout<gesture_cmd_t>().empty());
}

TEST(WireLengths, AnImageWhoseSizeSaysTwoGigabytesIsRejectedBeforeAnythingIsAllocated) {
  BusNode node("gpilot-test", "memq://");
  int frames = 0;
  node.subscribe<image_t>("CAMERA", [&](const image_t&, int64_t) { ++frames; });
  image_t im{};
  im.size = 4;
  im.data.assign(4, 1);
  std::vector<uint8_t> bytes = encoded(im);
  // the size field is the 4 bytes before the data (the last 4)
  const size_t at = bytes.size() - 4 - 4;
  for (const int32_t size : {INT32_MAX, -1, 5}) {
    const uint32_t u = static_cast<uint32_t>(size);
    bytes[at] = static_cast<uint8_t>(u >> 24), bytes[at + 1] = static_cast<uint8_t>(u >> 16);
    bytes[at + 2] = static_cast<uint8_t>(u >> 8), bytes[at + 3] = static_cast<uint8_t>(u);
    node.publish_raw("CAMERA", bytes.data(), bytes.size());
    node.drain();
    EXPECT_EQ(node.stats().last_reject_reason(), "CAMERA: " + std::to_string(bytes.size()) + " bytes do not decode as gpilot.image_t: " +
                                                     "an array length of " + std::to_string(size) + " with 4 bytes left");
  }
  EXPECT_EQ(frames, 0);
}

TEST(WireLengths, EveryLcmtypeWithAStringOrAnArrayHasALayout) {
  // The .lcm files say which types have variable-length fields: exactly the six with a layout.
  std::set<std::string> variable;
  for (const auto& f : std::filesystem::directory_iterator(std::string(GPILOT_SOURCE_DIR) + "/lcmtypes")) {
    if (f.path().extension() != ".lcm") continue;
    std::ifstream in(f.path());
    std::string line;
    const std::regex field(R"(^\s*(string\s+\w+|\w+\s+\w+\s*\[\s*[A-Za-z_]\w*\s*\])\s*;)");
    while (std::getline(in, line))
      if (std::regex_search(line, field)) variable.insert(f.path().stem().string());
  }
  EXPECT_EQ(variable, (std::set<std::string>{"autopilot_t", "config_t", "flight_control_t", "health_t", "image_t",
                                            "tracker_init_t"}))
      << "a type with a string or a variable array needs its layout in common/wire_lengths.cpp";
}

// A subscription decodes into one message, reused: a frame's vector keeps its buffer from frame to frame,
// yet nothing of a message leaks into the next (a 0-byte frame after a full one has no bytes; a HEALTH
// without a reject reason after one with).
TEST(ReusedDecode, AMessageCarriesNothingOfTheOneBefore) {
  BusNode node("gpilot-test", "memq://");
  std::vector<std::vector<uint8_t>> datas;
  std::vector<const uint8_t*> buffers;
  node.subscribe<image_t>("CAMERA", [&](const image_t& m, int64_t) {
    datas.push_back(m.data);
    buffers.push_back(m.data.data());
  });
  std::vector<std::string> reasons;
  node.subscribe<health_t>("HEALTH", [&](const health_t& h, int64_t) { reasons.push_back(h.last_reject_reason); });
  image_t a{};
  a.width = 2, a.height = 1, a.row_stride = 6, a.pixel_format = image_t::PIXEL_FORMAT_BGR8, a.size = 6;
  a.data = {1, 2, 3, 4, 5, 6};
  image_t b = a;
  b.data = {9, 8, 7, 6, 5, 4};
  image_t empty = a;
  empty.width = 0, empty.height = 0, empty.row_stride = 0, empty.size = 0, empty.data.clear();
  for (const image_t* m : {&a, &b}) {
    node.publish("CAMERA", *m);
    node.drain();
  }
  // WHEN a frame that check_message refuses (no pixels) follows, THEN it is rejected, not given with b's bytes
  node.publish("CAMERA", empty);
  node.drain();
  ASSERT_EQ(datas.size(), 2u);
  EXPECT_EQ(datas[0], a.data);
  EXPECT_EQ(datas[1], b.data);
  EXPECT_EQ(buffers[0], buffers[1]) << "the second frame is decoded into the first one's buffer";
  EXPECT_EQ(node.stats().rejected_count(), 1);
  health_t h{};
  h.name = "x", h.last_reject_reason = "one reason";
  node.publish("HEALTH", h);
  h.last_reject_reason = "";
  node.publish("HEALTH", h);
  node.drain();
  EXPECT_EQ(reasons, (std::vector<std::string>{"one reason", ""}));
}

// A handler that takes the message's bytes (swaps in a buffer of its own) keeps them; the next frame is
// decoded into the buffer it left.
TEST(ReusedDecode, ATakingHandlerKeepsTheBytesAndLendsItsBuffer) {
  BusNode node("gpilot-test", "memq://");
  std::vector<std::vector<uint8_t>> kept;
  std::vector<uint8_t> spare(6, 0);
  const uint8_t* spare_buffer = spare.data();
  std::vector<const uint8_t*> decoded_into;
  node.subscribe_taking<image_t>("CAMERA", [&](image_t& m, int64_t) {
    decoded_into.push_back(m.data.data());
    kept.emplace_back();
    kept.back().swap(m.data);
    m.data.swap(spare);  // spare is empty from the second frame on
  });
  image_t a{};
  a.width = 2, a.height = 1, a.row_stride = 6, a.pixel_format = image_t::PIXEL_FORMAT_BGR8, a.size = 6;
  a.data = {1, 2, 3, 4, 5, 6};
  image_t b = a;
  b.data = {9, 8, 7, 6, 5, 4};
  node.publish("CAMERA", a);
  node.publish("CAMERA", b);
  node.drain();
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0], a.data);
  EXPECT_EQ(kept[1], b.data);
  EXPECT_EQ(decoded_into[1], spare_buffer) << "frame b was decoded into the buffer the handler lent";
}
