// A UDP socket on 127.0.0.1 for tests that play the other end of a UDP link (a fake autopilot, a stranger
// sending forged datagrams): bound to a port of its own when made, a read waits at most 10 ms. The tests of
// gpilot-flight's MAVLink link share it instead of each spelling out the socket calls.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gpilot::test {

// 127.0.0.1:port (port 0: any free port, for bind).
inline sockaddr_in loopback_address(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<uint16_t>(port));
  return a;
}

// The port a socket is bound to (0 when it is not).
inline int local_port(int fd) {
  sockaddr_in a{};
  socklen_t n = sizeof a;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n) != 0) return 0;
  return ntohs(a.sin_port);
}

class UdpSocket {
 public:
  UdpSocket() : fd_(socket(AF_INET, SOCK_DGRAM, 0)) {
    const sockaddr_in a = loopback_address(0);
    bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a);
    port_ = local_port(fd_);
    timeval tv{0, 10000};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~UdpSocket() {
    if (fd_ >= 0) close(fd_);
  }
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  int port() const { return port_; }  // 0: the socket could not be made or bound

  void send_to(const sockaddr_in& to, const void* data, size_t size) {
    sendto(fd_, data, size, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  }
  void send_to(int port, const std::string& text) { send_to(loopback_address(port), text.data(), text.size()); }

  // One datagram, waiting up to 10 ms; false when none came. Its sender in *from when given.
  bool receive(std::vector<uint8_t>& out, sockaddr_in* from = nullptr) {
    out.resize(65536);
    sockaddr_in sender{};
    socklen_t n = sizeof sender;
    const ssize_t got = recvfrom(fd_, out.data(), out.size(), 0, reinterpret_cast<sockaddr*>(&sender), &n);
    out.resize(got > 0 ? static_cast<size_t>(got) : 0);
    if (got <= 0) return false;
    if (from) *from = sender;
    return true;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

}  // namespace gpilot::test
