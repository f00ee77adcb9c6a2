// MAVLink 2 message signing (mavlink.io/en/guide/message_signing.html): a 13-byte block after the CRC,
//   link id (1) | timestamp (6, little-endian, 10 µs units since 2015-01-01 UTC) | signature (6),
// the signature being the first 48 bits of SHA-256(secret key || the frame up to and with the timestamp)
// (OpenSSL). Incoming timestamps must grow per (system, component, link); a stream not heard before is
// accepted only within a minute of our clock, so a recorded frame cannot be replayed later.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace gpilot::mavlink {

// 10 µs units since 2015-01-01 00:00 UTC (MAVLink's signing clock) for a Unix time in µs.
uint64_t signing_timestamp(int64_t unix_utime);

class FrameSigner {
 public:
  FrameSigner(const std::array<uint8_t, 32>& key, uint8_t link_id) : key_(key), link_id_(link_id) {}
  // frame: one unsigned v2 frame from encode_frame (crc_extra of its message): sets the signed flag,
  // recomputes the CRC and appends the signature block. The timestamp grows by at least one per frame.
  void sign(std::vector<uint8_t>& frame, uint8_t crc_extra, int64_t now_utime);

 private:
  std::array<uint8_t, 32> key_;
  uint8_t link_id_;
  uint64_t last_ = 0;
};

class SignatureChecker {
 public:
  explicit SignatureChecker(const std::array<uint8_t, 32>& key) : key_(key) {}
  void set_now(int64_t unix_utime) { now_ = signing_timestamp(unix_utime); }
  // frame: total bytes of one signed v2 frame (CRC already checked). nullptr when valid, else the reason.
  const char* check(const uint8_t* frame, size_t total);

 private:
  std::array<uint8_t, 32> key_;
  uint64_t now_ = 0;
  std::map<std::tuple<uint8_t, uint8_t, uint8_t>, uint64_t> last_;  // (sysid, compid, link) -> timestamp
};

}  // namespace gpilot::mavlink
