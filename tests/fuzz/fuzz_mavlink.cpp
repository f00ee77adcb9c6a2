// Fuzz target: the MAVLink v2 frame parser on a byte stream cut into datagrams where the input says, then the
// payload decoders for each frame it accepts. Every accepted frame must encode again into one frame that a
// fresh parser accepts with the same id and payload; the parser must never run past its input.
#include <cstdint>
#include <vector>

#include "fuzz_input.hpp"
#include "mavlink/frame.hpp"
#include "mavlink/messages.hpp"

namespace mav = gpilot::mavlink;

namespace {

void decode(const mav::Frame& f) {
  switch (f.msgid) {
    case mav::Heartbeat::kId: (void)mav::unpack_heartbeat(f.payload); break;
    case mav::Attitude::kId: (void)mav::unpack_attitude(f.payload); break;
    case mav::LocalPositionNed::kId: (void)mav::unpack_local_position_ned(f.payload); break;
    case mav::CommandLong::kId: (void)mav::unpack_command_long(f.payload); break;
    case mav::CommandAck::kId: (void)mav::unpack_command_ack(f.payload); break;
    case mav::SetPositionTargetLocalNed::kId: (void)mav::unpack_set_position_target_local_ned(f.payload); break;
    case mav::ExtendedSysState::kId: (void)mav::unpack_extended_sys_state(f.payload); break;
    default: break;
  }
}

void round_trip(const mav::Frame& f) {
  const mav::MessageInfo* info = mav::message_info(f.msgid);
  if (!info) gpilot::fuzz::fail("an accepted frame has an unknown id");
  if (f.payload.size() != info->length) gpilot::fuzz::fail("an accepted payload is not zero-extended to its length");
  const std::vector<uint8_t> bytes = mav::encode_frame(f);
  mav::FrameParser again;
  int n = 0;
  again.feed(bytes.data(), bytes.size(), [&](const mav::Frame& g) {
    ++n;
    if (g.msgid != f.msgid || g.payload != f.payload || g.seq != f.seq || g.sysid != f.sysid || g.compid != f.compid)
      gpilot::fuzz::fail("a frame encoded again parses differently");
  });
  again.end_of_datagram();
  if (n != 1) gpilot::fuzz::fail("a frame encoded again does not parse as one frame");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  // First byte: how the stream is cut (0: one datagram; else datagrams of that many bytes, or a stream
  // when its top bit is set: no end_of_datagram between the pieces).
  const size_t piece = data[0] & 0x7F;
  const bool stream = data[0] & 0x80;
  ++data, --size;
  mav::FrameParser parser;
  const auto on_frame = [](const mav::Frame& f) {
    decode(f);
    round_trip(f);
  };
  for (size_t pos = 0; pos < size;) {
    const size_t n = piece == 0 ? size - pos : std::min(piece, size - pos);
    const std::vector<uint8_t> chunk(data + pos, data + pos + n);  // exactly n bytes: ASan sees any overread
    parser.feed(chunk.data(), chunk.size(), on_frame);
    if (!stream) parser.end_of_datagram();
    pos += n;
  }
  parser.end_of_datagram();
  return 0;
}
