#include "wire_lengths.hpp"

namespace gpilot {

namespace {

int32_t read_be32(const uint8_t* p) {
  return static_cast<int32_t>((static_cast<uint32_t>(p[0]) << 24) | (static_cast<uint32_t>(p[1]) << 16) |
                              (static_cast<uint32_t>(p[2]) << 8) | static_cast<uint32_t>(p[3]));
}

using P = WirePart;

}  // namespace

std::string check_wire_lengths(const void* data, size_t size, const std::vector<WirePart>& layout) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  size_t pos = 8;  // the fingerprint
  int64_t length = -1;  // the last kInt32Length field
  auto need = [&](size_t n) { return pos <= size && n <= size - pos; };
  for (const WirePart& part : layout) {
    switch (part.kind) {
      case P::kBytes:
        if (!need(static_cast<size_t>(part.bytes))) return "truncated";
        pos += static_cast<size_t>(part.bytes);
        break;
      case P::kInt32Length:
        if (!need(4)) return "truncated";
        length = read_be32(bytes + pos);
        pos += 4;
        break;
      case P::kString: {
        if (!need(4)) return "truncated";
        const int64_t n = read_be32(bytes + pos);  // with its NUL
        pos += 4;
        if (n < 1 || !need(static_cast<size_t>(n)))
          return "a string length of " + std::to_string(n) + " with " + std::to_string(size - pos) + " bytes left";
        pos += static_cast<size_t>(n);
        break;
      }
      case P::kByteArray:
        if (length < 0 || !need(static_cast<size_t>(length)))
          return "an array length of " + std::to_string(length) + " with " + std::to_string(size - pos) + " bytes left";
        pos += static_cast<size_t>(length);
        break;
    }
  }
  return pos == size ? "" : std::to_string(size - pos) + " bytes after the message";
}

// int64 utime, int64 seq, int8 command, float takeoff_altitude, string source
template <>
const std::vector<WirePart>& wire_layout<flight_control_t>() {
  static const std::vector<WirePart> l{{P::kBytes, 21}, {P::kString}};
  return l;
}
// int64 utime, int64 seq, int8 kind, boolean armed, int16 base_mode, int64 custom_mode, int8 system_status,
// string param_id, float param_value, int8 param_type
template <>
const std::vector<WirePart>& wire_layout<autopilot_t>() {
  static const std::vector<WirePart> l{{P::kBytes, 29}, {P::kString}, {P::kBytes, 5}};
  return l;
}
// int64 utime, int64 seq, int8 command, float box[4], string source
template <>
const std::vector<WirePart>& wire_layout<tracker_init_t>() {
  static const std::vector<WirePart> l{{P::kBytes, 33}, {P::kString}};
  return l;
}
// int64 utime, int64 seq, string name, int32 pid, int8 state, string state_detail, int64 messages_in,
// messages_out, rejected, dropped, string last_reject_reason, float rate_in_hz, rate_out_hz, p50, p99, double cpu_s
template <>
const std::vector<WirePart>& wire_layout<health_t>() {
  static const std::vector<WirePart> l{{P::kBytes, 16}, {P::kString}, {P::kBytes, 5}, {P::kString},
                                       {P::kBytes, 32}, {P::kString},  {P::kBytes, 24}};
  return l;
}
// int64 utime, int64 seq, int32 width, height, row_stride, int8 pixel_format, int32 size, byte data[size]
template <>
const std::vector<WirePart>& wire_layout<image_t>() {
  static const std::vector<WirePart> l{{P::kBytes, 29}, {P::kInt32Length}, {P::kByteArray}};
  return l;
}

// int64 utime, int64 seq, string process, int32 pid, string yaml
template <>
const std::vector<WirePart>& wire_layout<config_t>() {
  static const std::vector<WirePart> l{{P::kBytes, 16}, {P::kString}, {P::kBytes, 4}, {P::kString}};
  return l;
}

}  // namespace gpilot
