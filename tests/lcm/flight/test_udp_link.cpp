// The MAVLink UDP link reads vehicle state only from the autopilot's address: a datagram from any other
// sender on the network is skipped and counted (inside the test's network namespace, on 127.0.0.1).
#include <gtest/gtest.h>

#include <thread>

#include "mavlink/udp_link.hpp"
#include "udp_socket.hpp"

namespace gpilot::mavlink {
namespace {

TEST(UdpLink, ReadsOnlyTheAutopilotsDatagrams) {
  test::UdpSocket autopilot, stranger;
  UdpLink link(Endpoint{"127.0.0.1", autopilot.port()});
  ASSERT_TRUE(link.send({1, 2, 3}));  // the link's socket gets its port
  const int link_port = test::local_port(link.fd());
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
