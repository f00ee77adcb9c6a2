// UdpLink: one UDP socket to the autopilot at udp:HOST:PORT. Sends go there; whatever comes back to the
// same socket (PX4 SITL, mavlink-router answer the sender) is read without blocking.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "endpoint.hpp"

namespace gpilot::mavlink {

class UdpLink {
 public:
  explicit UdpLink(const Endpoint& endpoint);  // throws std::runtime_error when the socket cannot be made
  ~UdpLink();
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  bool send(const std::vector<uint8_t>& bytes);
  // One datagram from the endpoint into buf; false when none is waiting. Datagrams from any other address
  // are not the autopilot's: skipped and counted (foreign(), last_foreign()).
  bool receive(std::vector<uint8_t>& buf);
  int64_t foreign() const { return foreign_; }
  const std::string& last_foreign() const { return last_foreign_; }
  int fd() const { return fd_; }
  int64_t send_errors() const { return send_errors_; }

 private:
  int fd_ = -1;
  std::vector<uint8_t> addr_;  // sockaddr_in of the endpoint
  int64_t send_errors_ = 0;
  int64_t foreign_ = 0;
  std::string last_foreign_;
};

}  // namespace gpilot::mavlink
