// Bytes <-> lowercase hex text, for logs, test vectors and the node-mavlink peer's pipes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gpilot::mavlink {

inline std::string to_hex(const std::vector<uint8_t>& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  s.reserve(bytes.size() * 2);
  for (uint8_t v : bytes) {
    s += digits[v >> 4];
    s += digits[v & 15];
  }
  return s;
}

// Pairs of hex digits; stops at the first pair that is not hex.
inline std::vector<uint8_t> from_hex(const std::string& text) {
  auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::vector<uint8_t> out;
  for (size_t i = 0; i + 1 < text.size(); i += 2) {
    const int hi = nibble(text[i]), lo = nibble(text[i + 1]);
    if (hi < 0 || lo < 0) break;
    out.push_back(static_cast<uint8_t>(hi << 4 | lo));
  }
  return out;
}

}  // namespace gpilot::mavlink
