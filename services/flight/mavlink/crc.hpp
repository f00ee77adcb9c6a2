// CRC-16/MCRF4XX (MAVLink's "X.25" checksum): over the frame after the magic byte, then the message's CRC_EXTRA.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gpilot::mavlink {

constexpr uint16_t kCrcInit = 0xFFFF;

constexpr uint16_t crc_accumulate(uint8_t byte, uint16_t crc) {
  uint8_t t = static_cast<uint8_t>(byte ^ (crc & 0xFF));
  t = static_cast<uint8_t>(t ^ (t << 4));
  return static_cast<uint16_t>((crc >> 8) ^ (t << 8) ^ (t << 3) ^ (t >> 4));
}

inline uint16_t crc_x25(const uint8_t* data, size_t n, uint16_t crc = kCrcInit) {
  for (size_t i = 0; i < n; ++i) crc = crc_accumulate(data[i], crc);
  return crc;
}

}  // namespace gpilot::mavlink
