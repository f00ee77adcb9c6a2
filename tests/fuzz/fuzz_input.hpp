// Reads a fuzzer's bytes as typed values, front to back; past the end every read gives zero, so any input is
// a valid (if short) sequence. Floats are raw bit patterns: NaN, infinities and denormals come out too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace gpilot::fuzz {

class Input {
 public:
  Input(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  bool empty() const { return pos_ >= size_; }
  size_t left() const { return pos_ < size_ ? size_ - pos_ : 0; }

  template <class T>
  T raw() {
    T v{};
    uint8_t b[sizeof(T)] = {};
    for (size_t i = 0; i < sizeof(T) && pos_ < size_; ++i) b[i] = data_[pos_++];
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  uint8_t byte() { return raw<uint8_t>(); }
  bool flag() { return byte() & 1; }
  // lo..hi inclusive (hi - lo < 2^32).
  int64_t in(int64_t lo, int64_t hi) {
    const uint64_t span = static_cast<uint64_t>(hi - lo) + 1;
    return lo + static_cast<int64_t>(raw<uint32_t>() % span);
  }
  float f32() { return raw<float>(); }
  // A float that is usually a plausible pixel value (0..2047.75 in quarter pixels) and sometimes any bit
  // pattern, so both the accepted paths and the rejections are reached.
  float coordinate() {
    const uint8_t kind = byte();
    if (kind < 224) return static_cast<float>(raw<uint16_t>() % 8192) / 4.0f;
    return f32();
  }
  std::vector<uint8_t> bytes(size_t n) {
    const size_t k = n < left() ? n : left();
    std::vector<uint8_t> out(data_ + pos_, data_ + pos_ + k);
    pos_ += k;
    return out;
  }
  std::vector<uint8_t> rest() { return bytes(left()); }
  std::string text(size_t max) {
    const size_t n = static_cast<size_t>(in(0, static_cast<int64_t>(max)));
    const auto b = bytes(n);
    return std::string(b.begin(), b.end());
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

// A broken invariant: prints why and aborts, which libFuzzer (and the corpus test) report as a crash.
[[noreturn]] void fail(const std::string& why);

}  // namespace gpilot::fuzz
