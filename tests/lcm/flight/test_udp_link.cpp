// The MAVLink UDP link reads vehicle state only from the autopilot's address: a datagram from any other
// sender on the network is skipped and counted (inside the test's network namespace, on 127.0.0.1).
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include "mavlink/udp_link.hpp"

namespace gpilot::mavlink {
namespace {

struct Socket {
  int fd = socket(AF_INET, SOCK_DGRAM, 0);
  ~Socket() { close(fd); }
  int bind_any() {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t n = sizeof a;
    getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
    return ntohs(a.sin_port);
  }
  void send_to(int port, const std::string& text) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<uint16_t>(port));
    sendto(fd, text.data(), text.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
  }
};

int local_port(int fd) {
  sockaddr_in a{};
  socklen_t n = sizeof a;
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  return ntohs(a.sin_port);
}

TEST(UdpLink, ReadsOnlyTheAutopilotsDatagrams) {
  Socket autopilot, stranger;
  const int port = autopilot.bind_any();
  stranger.bind_any();
  UdpLink link(Endpoint{"127.0.0.1", port});
  ASSERT_TRUE(link.send({1, 2, 3}));  // the link's socket gets its port
  const int link_port = local_port(link.fd());
  ASSERT_GT(link_port, 0);
  // GIVEN a stranger's datagram, then the autopilot's
  stranger.send_to(link_port, "forged vehicle state");
  autopilot.send_to(link_port, "from the autopilot");
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // loopback delivery, not a timing assertion
  // THEN only the autopilot's is read, and the stranger's is counted with its address
  std::vector<uint8_t> buf;
  ASSERT_TRUE(link.receive(buf));
  EXPECT_EQ(std::string(buf.begin(), buf.end()), "from the autopilot");
  EXPECT_FALSE(link.receive(buf));
  EXPECT_EQ(link.foreign(), 1);
  EXPECT_EQ(link.last_foreign().rfind("127.0.0.1:", 0), 0u) << link.last_foreign();
}

}  // namespace
}  // namespace gpilot::mavlink
