// Signed bus messages. With a bus key, every message carries a 56-byte trailer after its LCM encoding:
//   "GPS1" | key id (u32) | sender (u64, random per process start) | time (i64, µs on the sender's clock,
//   strictly increasing per sender) | HMAC-SHA-256 (OpenSSL) over the channel name, a zero byte, the
//   message and the 24 header bytes above.
// LCM's decoders (C++, Java for lcm-spy, Python) stop at the message's end, so spy, logger and log readers
// see the message as before. The channel is signed, so a message cannot be replayed on another channel;
// the time must grow per sender and lie within a window of the arrival, so a recorded message cannot be
// replayed later (MAVLink 2 signing's rule, with the window for a receiver that just started).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "bus_key.hpp"

namespace gpilot {

constexpr size_t kSignatureBytes = 56;

// Size of the message in size bytes that end in a signature trailer (unverified), else size.
size_t message_size_of(const void* data, size_t size);

class BusMac;

class BusSigner {
 public:
  BusSigner(const BusKey& key, uint64_t sender);
  ~BusSigner();
  // Appends the trailer after size bytes of buf (which has room for kSignatureBytes more) and returns the
  // signed size. now_utime is the sender's clock; the signature time is at least one past the last one.
  size_t sign(const std::string& channel, uint8_t* buf, size_t size, int64_t now_utime);
  uint64_t sender() const { return sender_; }

 private:
  uint32_t key_id_;
  std::unique_ptr<BusMac> mac_;
  uint64_t sender_;
  int64_t last_time_ = 0;
};

class BusVerifier {
 public:
  struct Result {
    std::string why;            // "" when valid
    size_t message_size = 0;    // the message's bytes before the trailer
    uint64_t sender = 0;
  };
  // keys: accepted keys (the signing key and a previous one while rotating).
  BusVerifier(const std::vector<BusKey>& keys, int64_t window_us);
  ~BusVerifier();
  Result verify(const std::string& channel, const void* data, size_t size, int64_t arrival_utime);
  uint64_t senders() const { return last_time_.size(); }

 private:
  struct Keyed {
    uint32_t id;
    std::unique_ptr<BusMac> mac;
  };
  std::vector<Keyed> keys_;
  int64_t window_us_;
  std::unordered_map<uint64_t, int64_t> last_time_;  // per sender; bounded (kMaxSenders)
};

// One random 64-bit sender id per process start (OpenSSL RAND_bytes).
uint64_t random_sender_id();

}  // namespace gpilot
