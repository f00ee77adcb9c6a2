#include "signing.hpp"

#include <algorithm>
#include <cstring>

#include <openssl/crypto.h>
#include <openssl/evp.h>

#include "crc.hpp"
#include "frame.hpp"

namespace gpilot::mavlink {
namespace {

constexpr int64_t kEpoch2015Utime = 1420070400LL * 1000000;  // 2015-01-01 00:00:00 UTC
constexpr uint64_t kNewStreamWindow = 60ULL * 100000;        // a minute, in 10 µs units
constexpr size_t kSigBytes = 6;

// SHA-256(key || data)[0:6]
void signature_of(const std::array<uint8_t, 32>& key, const uint8_t* data, size_t n, uint8_t* out) {
  uint8_t digest[32];
  unsigned int len = 0;
  EVP_MD_CTX* c = EVP_MD_CTX_new();
  const bool ok = c && EVP_DigestInit_ex(c, EVP_sha256(), nullptr) == 1 &&
                  EVP_DigestUpdate(c, key.data(), key.size()) == 1 && EVP_DigestUpdate(c, data, n) == 1 &&
                  EVP_DigestFinal_ex(c, digest, &len) == 1;
  EVP_MD_CTX_free(c);
  if (!ok) std::memset(digest, 0, sizeof digest);  // never matches a real signature by chance
  std::memcpy(out, digest, kSigBytes);
}

}  // namespace

uint64_t signing_timestamp(int64_t unix_utime) {
  return unix_utime > kEpoch2015Utime ? static_cast<uint64_t>(unix_utime - kEpoch2015Utime) / 10 : 0;
}

void FrameSigner::sign(std::vector<uint8_t>& frame, uint8_t crc_extra, int64_t now_utime) {
  const size_t len = frame[1];
  frame[2] |= kIncompatSigned;  // the flag is in the CRC
  uint16_t crc = crc_x25(frame.data() + 1, kHeaderLength - 1 + len);
  crc = crc_accumulate(crc_extra, crc);
  frame[kHeaderLength + len] = static_cast<uint8_t>(crc);
  frame[kHeaderLength + len + 1] = static_cast<uint8_t>(crc >> 8);
  last_ = std::max(signing_timestamp(now_utime), last_ + 1);
  frame.push_back(link_id_);
  for (int i = 0; i < 6; ++i) frame.push_back(static_cast<uint8_t>(last_ >> (8 * i)));
  uint8_t sig[kSigBytes];
  signature_of(key_, frame.data(), frame.size(), sig);
  frame.insert(frame.end(), sig, sig + kSigBytes);
}

const char* SignatureChecker::check(const uint8_t* frame, size_t total) {
  if (total < kHeaderLength + 2 + kSignatureLength) return "signed frame too short";
  uint8_t sig[kSigBytes];
  signature_of(key_, frame, total - kSigBytes, sig);
  if (CRYPTO_memcmp(sig, frame + total - kSigBytes, kSigBytes) != 0) return "bad signature (wrong key or altered)";
  const uint8_t* block = frame + total - kSignatureLength;
  uint64_t ts = 0;
  for (int i = 5; i >= 0; --i) ts = (ts << 8) | block[1 + i];
  const auto stream = std::make_tuple(frame[5], frame[6], block[0]);
  const auto it = last_.find(stream);
  if (it != last_.end()) {
    if (ts <= it->second) return "replayed signed frame (its timestamp is not after the link's last)";
  } else if (ts + kNewStreamWindow < now_) {
    return "signed frame more than a minute old on a new link (a replay)";
  }
  last_[stream] = ts;
  return nullptr;
}

}  // namespace gpilot::mavlink
