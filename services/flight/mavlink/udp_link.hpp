// UdpLink: one UDP socket to the autopilot at udp:HOST:PORT. Sends go there; whatever comes back to the
// same socket (PX4 SITL, mavlink-router answer the sender) is read without blocking.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gpilot::mavlink {

struct Endpoint {
  std::string host;
  int port = 0;
};

// "udp:HOST:PORT" -> Endpoint; throws std::invalid_argument with the reason.
Endpoint parse_endpoint(const std::string& text);

class UdpLink {
 public:
  explicit UdpLink(const Endpoint& endpoint);  // throws std::runtime_error when the socket cannot be made
  ~UdpLink();
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  bool send(const std::vector<uint8_t>& bytes);
  // One datagram into buf; false when none is waiting.
  bool receive(std::vector<uint8_t>& buf);
  int fd() const { return fd_; }
  int64_t send_errors() const { return send_errors_; }

 private:
  int fd_ = -1;
  std::vector<uint8_t> addr_;  // sockaddr_in of the endpoint
  int64_t send_errors_ = 0;
};

}  // namespace gpilot::mavlink
