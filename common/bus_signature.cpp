#include "bus_signature.hpp"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <cstring>
#include <stdexcept>

#include <openssl/core_names.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/params.h>
#include <openssl/rand.h>

namespace gpilot {
namespace {

constexpr char kMagic[4] = {'G', 'P', 'S', '1'};
constexpr size_t kHeaderBytes = 24;  // magic, key id, sender, time
constexpr size_t kMacBytes = 32;
static_assert(kHeaderBytes + kMacBytes == kSignatureBytes, "trailer layout");
constexpr size_t kMaxSenders = 4096;  // a flood of made-up sender ids cannot grow the table without bound

void put_be(uint8_t* p, uint64_t v, int n) {
  for (int i = n - 1; i >= 0; --i, v >>= 8) p[i] = static_cast<uint8_t>(v & 0xff);
}
uint64_t get_be(const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

// HMAC-SHA-256 keyed once (OpenSSL 3's EVP_MAC); each message works on a copy of the keyed context.
class BusMac {
 public:
  explicit BusMac(const BusKey& key) {
    alg_ = EVP_MAC_fetch(nullptr, "HMAC", nullptr);
    keyed_ = alg_ ? EVP_MAC_CTX_new(alg_) : nullptr;
    OSSL_PARAM params[] = {OSSL_PARAM_construct_utf8_string("digest", const_cast<char*>("SHA256"), 0),
                           OSSL_PARAM_construct_end()};
    if (!keyed_ || EVP_MAC_init(keyed_, key.bytes.data(), key.bytes.size(), params) != 1) {
      EVP_MAC_CTX_free(keyed_);
      EVP_MAC_free(alg_);
      throw std::runtime_error("HMAC-SHA-256 is not available (OpenSSL)");
    }
  }
  ~BusMac() {
    EVP_MAC_CTX_free(keyed_);
    EVP_MAC_free(alg_);
  }
  BusMac(const BusMac&) = delete;
  BusMac& operator=(const BusMac&) = delete;

  // mac = HMAC(key, channel || 0 || message || header)
  void compute(const std::string& channel, const uint8_t* message, size_t size, const uint8_t* header, uint8_t* mac) const {
    EVP_MAC_CTX* c = EVP_MAC_CTX_dup(keyed_);
    size_t out = 0;
    const uint8_t zero = 0;
    const bool ok = c && EVP_MAC_update(c, reinterpret_cast<const uint8_t*>(channel.data()), channel.size()) == 1 &&
                    EVP_MAC_update(c, &zero, 1) == 1 && EVP_MAC_update(c, message, size) == 1 &&
                    EVP_MAC_update(c, header, kHeaderBytes) == 1 && EVP_MAC_final(c, mac, &out, kMacBytes) == 1;
    EVP_MAC_CTX_free(c);
    if (!ok || out != kMacBytes) throw std::runtime_error("HMAC-SHA-256 failed (OpenSSL)");
  }

 private:
  EVP_MAC* alg_ = nullptr;
  EVP_MAC_CTX* keyed_ = nullptr;
};

uint64_t random_sender_id() {
  uint8_t b[8];
  if (RAND_bytes(b, sizeof b) != 1) throw std::runtime_error("no randomness for a bus sender id (OpenSSL RAND_bytes failed)");
  return get_be(b, 8);
}

size_t message_size_of(const void* data, size_t size) {
  if (size < kSignatureBytes) return size;
  const auto* t = static_cast<const uint8_t*>(data) + size - kSignatureBytes;
  return std::memcmp(t, kMagic, sizeof kMagic) == 0 ? size - kSignatureBytes : size;
}

BusSigner::BusSigner(const BusKey& key, uint64_t sender)
    : key_id_(key.id), mac_(std::make_unique<BusMac>(key)), sender_(sender) {}
BusSigner::~BusSigner() = default;

size_t BusSigner::sign(const std::string& channel, uint8_t* buf, size_t size, int64_t now_utime) {
  last_time_ = std::max(now_utime, last_time_ + 1);
  uint8_t* t = buf + size;
  std::memcpy(t, kMagic, sizeof kMagic);
  put_be(t + 4, key_id_, 4);
  put_be(t + 8, sender_, 8);
  put_be(t + 16, static_cast<uint64_t>(last_time_), 8);
  mac_->compute(channel, buf, size, t, t + kHeaderBytes);
  return size + kSignatureBytes;
}

BusVerifier::BusVerifier(const std::vector<BusKey>& keys, int64_t window_us) : window_us_(window_us) {
  for (const auto& k : keys) keys_.push_back({k.id, std::make_unique<BusMac>(k)});
}
BusVerifier::~BusVerifier() = default;

BusVerifier::Result BusVerifier::verify(const std::string& channel, const void* data, size_t size, int64_t arrival_utime) {
  Result r;
  if (message_size_of(data, size) == size) {
    r.why = "unsigned (this bus needs every message signed with its key)";
    return r;
  }
  const auto* bytes = static_cast<const uint8_t*>(data);
  const uint8_t* t = bytes + size - kSignatureBytes;
  const uint32_t key_id = static_cast<uint32_t>(get_be(t + 4, 4));
  const BusMac* key = nullptr;
  for (const auto& k : keys_)
    if (k.id == key_id) key = k.mac.get();
  char id[16];
  std::snprintf(id, sizeof id, "%08x", key_id);
  if (!key) {
    r.why = std::string("signed with an unknown key (id ") + id + ")";
    return r;
  }
  uint8_t mac[kMacBytes];
  key->compute(channel, bytes, size - kSignatureBytes, t, mac);
  if (CRYPTO_memcmp(mac, t + kHeaderBytes, kMacBytes) != 0) {
    r.why = "bad signature (forged, altered, or sent on another channel)";
    return r;
  }
  r.sender = get_be(t + 8, 8);
  const int64_t time = static_cast<int64_t>(get_be(t + 16, 8));
  if (time < arrival_utime - window_us_ || time > arrival_utime + window_us_) {
    r.why = "signed " + std::to_string((arrival_utime - time) / 1000) + " ms before its arrival (outside bus.time_window_s: a replay or a clock far off)";
    return r;
  }
  auto it = last_time_.find(r.sender);
  if (it != last_time_.end() && time <= it->second) {
    r.why = "replayed or reordered (its signature time is not after this sender's last)";
    return r;
  }
  if (it == last_time_.end() && last_time_.size() >= kMaxSenders) {
    // Forget senders silent for longer than the window: their old messages are out of the window anyway.
    for (auto i = last_time_.begin(); i != last_time_.end();)
      i = i->second < arrival_utime - window_us_ ? last_time_.erase(i) : std::next(i);
    if (last_time_.size() >= kMaxSenders) {
      r.why = "too many senders within the time window";
      return r;
    }
  }
  last_time_[r.sender] = time;
  r.message_size = size - kSignatureBytes;
  return r;
}

}  // namespace gpilot
