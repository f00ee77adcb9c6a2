// UdpLink: a plain IPv4 datagram socket, non-blocking receive.
#include "udp_link.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace gpilot::mavlink {

UdpLink::UdpLink(const Endpoint& endpoint) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* res = nullptr;
  const int rc = getaddrinfo(endpoint.host.c_str(), std::to_string(endpoint.port).c_str(), &hints, &res);
  if (rc != 0 || !res)
    throw std::runtime_error("MAVLink endpoint host '" + endpoint.host + "': " + gai_strerror(rc));
  addr_.assign(reinterpret_cast<const uint8_t*>(res->ai_addr),
               reinterpret_cast<const uint8_t*>(res->ai_addr) + res->ai_addrlen);
  freeaddrinfo(res);
  fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("MAVLink UDP socket: ") + std::strerror(errno));
}

UdpLink::~UdpLink() {
  if (fd_ >= 0) close(fd_);
}

bool UdpLink::send(const std::vector<uint8_t>& bytes) {
  const ssize_t n = sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(addr_.data()),
                           static_cast<socklen_t>(addr_.size()));
  // An autopilot that is not up yet answers with ICMP unreachable (ECONNREFUSED on a later call): counted,
  // and the link keeps trying.
  if (n != static_cast<ssize_t>(bytes.size())) {
    ++send_errors_;
    return false;
  }
  return true;
}

bool UdpLink::receive(std::vector<uint8_t>& buf) {
  const auto& want = *reinterpret_cast<const sockaddr_in*>(addr_.data());
  for (;;) {
    buf.resize(65536);
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = recvfrom(fd_, buf.data(), buf.size(), 0, reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n < 0) {
      buf.clear();
      return false;
    }
    if (from.sin_addr.s_addr == want.sin_addr.s_addr && from.sin_port == want.sin_port) {
      buf.resize(static_cast<size_t>(n));
      return true;
    }
    ++foreign_;
    char ip[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &from.sin_addr, ip, sizeof ip);
    last_foreign_ = std::string(ip) + ":" + std::to_string(ntohs(from.sin_port));
  }
}

}  // namespace gpilot::mavlink
