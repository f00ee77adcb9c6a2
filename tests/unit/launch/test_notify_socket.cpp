// gpilot-launch's watchdog input: systemd's notify protocol on a socket of its own. The datagrams are parsed as
// sd_notify writes them; only the watched process's own datagrams count (the kernel's SO_PASSCRED pid).
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <string>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include "notify_socket.hpp"
#include "service_set.hpp"

namespace gpilot {
namespace {

// Sends text to NOTIFY_SOCKET-style address (leading '@': abstract), as libsystemd's sd_notify does.
void notify(const std::string& address, const std::string& text) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, address.data(), address.size());
  if (address[0] == '@') addr.sun_path[0] = 0;
  const int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  const socklen_t len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + address.size());
  EXPECT_EQ(sendto(fd, text.data(), text.size(), 0, reinterpret_cast<const sockaddr*>(&addr), len),
            static_cast<ssize_t>(text.size()));
  close(fd);
}

TEST(Notify, ParsesTheAssignmentsSdNotifyWrites) {
  EXPECT_TRUE(parse_notify("READY=1").ready);
  const NotifyState s = parse_notify("STATUS=flying\nWATCHDOG=1\n");
  EXPECT_TRUE(s.watchdog);
  EXPECT_FALSE(s.ready);
  EXPECT_FALSE(s.stopping);
  EXPECT_TRUE(parse_notify("STOPPING=1").stopping);
  EXPECT_FALSE(parse_notify("READY=0\nWATCHDOG=trigger").any());
  EXPECT_FALSE(parse_notify("").any());
}

TEST(Notify, CountsOnlyTheWatchedProcess) {
  NotifySocket sock("test-" + std::to_string(getpid()));
  ASSERT_EQ(sock.address().rfind("@gpilot-launch-", 0), 0u) << sock.address();
  EXPECT_FALSE(sock.poll(getpid()).any());  // nothing sent yet: no block, nothing read

  // GIVEN this process pings, WHEN polled for this pid THEN it counts
  notify(sock.address(), "READY=1");
  notify(sock.address(), "WATCHDOG=1");
  NotifyState s = sock.poll(getpid());
  EXPECT_TRUE(s.ready);
  EXPECT_TRUE(s.watchdog);
  EXPECT_EQ(sock.foreign(), 0);

  // GIVEN another process (a child) pings, WHEN polled for this pid THEN it is ignored and counted as foreign
  const pid_t child = fork();
  if (child == 0) {
    notify(sock.address(), "WATCHDOG=1");
    _exit(0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  s = sock.poll(getpid());
  EXPECT_FALSE(s.any());
  EXPECT_EQ(sock.foreign(), 1);
}

TEST(Notify, WatchdogInServicesFileAndSystemdUnit) {
  const auto s = parse_service_set("services:\n  - name: f\n    command: [gpilot-flight]\n    watchdog_s: 0.5\n", {});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_DOUBLE_EQ(s[0].watchdog_s, 0.5);
  const std::string unit = systemd_unit(s[0], "/opt/b", "", "u");
  EXPECT_NE(unit.find("Type=notify\nWatchdogSec=500ms\nWatchdogSignal=SIGKILL\n"), std::string::npos) << unit;
  ServiceSpec plain;
  plain.name = "x";
  plain.command = {"x"};
  EXPECT_EQ(systemd_unit(plain, "/opt/b", "", "u").find("Watchdog"), std::string::npos);
  EXPECT_THROW(parse_service_set("services:\n  - name: f\n    command: [x]\n    watchdog_s: -1\n", {}), ServiceSetError);
}

}  // namespace
}  // namespace gpilot
