// The string and array lengths of an LCM datagram, checked before LCM 1.3.1's generated decoder runs: that
// decoder trusts them, and a string length of INT32_MIN makes it read ~2 GB past a 33-byte datagram (a
// segfault no try/catch stops), an array length of 2^31-1 makes it allocate 2 GB before it notices the
// datagram is short. Each of our types with a string or an array declares its wire layout here (a test
// encodes each type and checks the layout walks it exactly); the other types have fixed sizes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gpilot/autopilot_t.hpp"
#include "gpilot/config_t.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/tracker_init_t.hpp"

namespace gpilot {

// One run of the wire format after the 8-byte fingerprint.
struct WirePart {
  enum Kind { kBytes, kInt32Length, kString, kByteArray } kind;
  int bytes = 0;  //!< kBytes: how many fixed bytes
};

// "" when every length in data fits the datagram (and the parts end exactly at its end), else why not.
std::string check_wire_lengths(const void* data, size_t size, const std::vector<WirePart>& layout);

// The layout of Msg, or empty for a type without strings or arrays.
template <class Msg>
const std::vector<WirePart>& wire_layout() {
  static const std::vector<WirePart> fixed;
  return fixed;
}
template <>
const std::vector<WirePart>& wire_layout<flight_control_t>();
template <>
const std::vector<WirePart>& wire_layout<tracker_init_t>();
template <>
const std::vector<WirePart>& wire_layout<health_t>();
template <>
const std::vector<WirePart>& wire_layout<image_t>();
template <>
const std::vector<WirePart>& wire_layout<config_t>();
template <>
const std::vector<WirePart>& wire_layout<autopilot_t>();

template <class Msg>
std::string check_wire_lengths(const void* data, size_t size) {
  const auto& layout = wire_layout<Msg>();
  return layout.empty() ? std::string() : check_wire_lengths(data, size, layout);
}

}  // namespace gpilot
