// Little-endian field packing for MAVLink payloads (the wire order is fixed by the message, all fields LE).
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace gpilot::mavlink {

class Writer {
 public:
  explicit Writer(std::vector<uint8_t>& out) : out_(out) {}
  Writer& u8(uint8_t v) { return bytes(&v, 1); }
  Writer& u16(uint16_t v) { return le(v); }
  Writer& u32(uint32_t v) { return le(v); }
  Writer& i32(int32_t v) { return le(static_cast<uint32_t>(v)); }
  Writer& f32(float v) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    return le(u);
  }

 private:
  template <class U>
  Writer& le(U v) {
    uint8_t b[sizeof(U)];
    for (size_t i = 0; i < sizeof(U); ++i) b[i] = static_cast<uint8_t>(v >> (8 * i));
    return bytes(b, sizeof(U));
  }
  Writer& bytes(const uint8_t* b, size_t n) {
    out_.insert(out_.end(), b, b + n);
    return *this;
  }
  std::vector<uint8_t>& out_;
};

// Reads a payload that the frame parser has already zero-extended to the message's full length.
class Reader {
 public:
  explicit Reader(const std::vector<uint8_t>& in) : in_(in) {}
  uint8_t u8() { return static_cast<uint8_t>(le(1)); }
  uint16_t u16() { return static_cast<uint16_t>(le(2)); }
  uint32_t u32() { return static_cast<uint32_t>(le(4)); }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  float f32() {
    const uint32_t u = u32();
    float v;
    std::memcpy(&v, &u, 4);
    return v;
  }

 private:
  uint64_t le(size_t n) {
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) {
      const uint8_t b = pos_ < in_.size() ? in_[pos_] : 0;  // v2 truncation: missing bytes are zeros
      v |= static_cast<uint64_t>(b) << (8 * i);
      ++pos_;
    }
    return v;
  }
  const std::vector<uint8_t>& in_;
  size_t pos_ = 0;
};

}  // namespace gpilot::mavlink
