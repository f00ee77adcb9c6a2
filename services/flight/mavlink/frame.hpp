// MAVLink v2 framing: encode one frame (with v2 trailing-zero truncation) and a byte-stream parser that
// checks length and CRC against the known-message table and counts what it rejects.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace gpilot::mavlink {

constexpr uint8_t kMagicV2 = 0xFD;
constexpr size_t kHeaderLength = 10;  // magic, len, incompat, compat, seq, sysid, compid, msgid[3]
constexpr size_t kSignatureLength = 13;
constexpr uint8_t kIncompatSigned = 0x01;

struct Frame {
  uint8_t seq = 0;
  uint8_t sysid = 0;
  uint8_t compid = 0;
  uint32_t msgid = 0;
  std::vector<uint8_t> payload;  //!< as received (maybe truncated) or as to be sent (full length)
};

// The frame bytes; msgid must be in the message table (throws std::invalid_argument otherwise).
std::vector<uint8_t> encode_frame(const Frame& frame);

struct ParserCounts {
  int64_t frames = 0;        //!< accepted
  int64_t bad_crc = 0;
  int64_t bad_length = 0;    //!< payload longer than the message's
  int64_t unknown_id = 0;    //!< a message gpilot does not decode (CRC cannot be checked)
  int64_t unsupported = 0;   //!< signed frames or unknown incompatibility flags
  int64_t skipped_bytes = 0; //!< bytes outside any frame (garbage, v1 frames, resynchronisation)
  int64_t truncated = 0;     //!< a datagram that ended inside a frame
  int64_t bad_signature = 0; //!< signing on: a signature that does not verify, or a replayed timestamp
  int64_t unsigned_frames = 0;  //!< signing on: a frame without a signature
};

class SignatureChecker;

class FrameParser {
 public:
  // Feeds bytes (a datagram or part of a stream); calls on_frame for each valid frame, payload zero-extended
  // to the message's full length. A partial frame at the end waits for the next call.
  void feed(const uint8_t* data, size_t n, const std::function<void(const Frame&)>& on_frame);
  // A datagram holds whole frames: whatever is left of one at its end is a truncated frame, dropped.
  void end_of_datagram();
  const ParserCounts& counts() const { return counts_; }
  int64_t rejected() const {
    return counts_.bad_crc + counts_.bad_length + counts_.unknown_id + counts_.unsupported + counts_.truncated +
           counts_.bad_signature + counts_.unsigned_frames;
  }
  // With a checker (MAVLink 2 signing, signing.hpp), only frames with a valid signature pass; without one,
  // signed frames cannot be checked and are rejected.
  void require_signatures(SignatureChecker* checker) { checker_ = checker; }
  // The reason of the last rejection ("bad CRC for LOCAL_POSITION_NED", ...), "" if none yet.
  const char* last_reject() const { return last_reject_; }

 private:
  void drop(size_t n);
  std::vector<uint8_t> buf_;
  ParserCounts counts_;
  SignatureChecker* checker_ = nullptr;
  const char* last_reject_ = "";
};

}  // namespace gpilot::mavlink
