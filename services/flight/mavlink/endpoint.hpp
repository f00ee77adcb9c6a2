// The autopilot's address as the config writes it (mavlink.endpoint: "udp:HOST:PORT"). Header-only, without
// sockets: MavlinkParams::check() parses it when the config is validated, before any process touches the bus.
#pragma once

#include <stdexcept>
#include <string>

namespace gpilot::mavlink {

struct Endpoint {
  std::string host;
  int port = 0;
};

// "udp:HOST:PORT" -> Endpoint; throws std::invalid_argument with the reason.
inline Endpoint parse_endpoint(const std::string& text) {
  const std::string prefix = "udp:";
  if (text.compare(0, prefix.size(), prefix) != 0)
    throw std::invalid_argument("MAVLink endpoint '" + text + "' must be udp:HOST:PORT");
  const std::string rest = text.substr(prefix.size());
  const size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw std::invalid_argument("MAVLink endpoint '" + text + "' must be udp:HOST:PORT");
  Endpoint e;
  e.host = rest.substr(0, colon);
  const std::string port = rest.substr(colon + 1);
  if (port.empty() || port.find_first_not_of("0123456789") != std::string::npos || port.size() > 5 ||
      std::stoi(port) < 1 || std::stoi(port) > 65535)
    throw std::invalid_argument("MAVLink endpoint '" + text + "': port must be 1..65535");
  e.port = std::stoi(port);
  return e;
}

}  // namespace gpilot::mavlink
