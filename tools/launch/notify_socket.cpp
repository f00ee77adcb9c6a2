#include "notify_socket.hpp"

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

namespace gpilot {

NotifyState parse_notify(const std::string& text) {
  NotifyState s;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line == "READY=1") s.ready = true;
    else if (line == "WATCHDOG=1") s.watchdog = true;
    else if (line == "STOPPING=1") s.stopping = true;
  }
  return s;
}

NotifySocket::NotifySocket(const std::string& name) {
  const std::string abstract = "gpilot-launch-" + std::to_string(getpid()) + "-" + name;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (abstract.size() + 1 > sizeof addr.sun_path) throw std::runtime_error("notify socket name too long: " + abstract);
  std::memcpy(addr.sun_path + 1, abstract.data(), abstract.size());  // sun_path[0] = 0: abstract namespace
  fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("notify socket: ") + std::strerror(errno));
  const int on = 1;
  const socklen_t len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + abstract.size());
  if (setsockopt(fd_, SOL_SOCKET, SO_PASSCRED, &on, sizeof on) != 0 ||
      bind(fd_, reinterpret_cast<const sockaddr*>(&addr), len) != 0) {
    const std::string why = std::strerror(errno);
    close(fd_);
    throw std::runtime_error("notify socket @" + abstract + ": " + why);
  }
  address_ = "@" + abstract;
}

NotifySocket::~NotifySocket() {
  if (fd_ >= 0) close(fd_);
}

NotifyState NotifySocket::poll(pid_t pid) {
  NotifyState out;
  for (;;) {
    char buf[4096];
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(ucred))];
    iovec iov{buf, sizeof buf - 1};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EINTR) continue;
      return out;  // EAGAIN: nothing more waiting
    }
    pid_t sender = -1;
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_CREDENTIALS) {
        ucred cred;
        std::memcpy(&cred, CMSG_DATA(c), sizeof cred);
        sender = cred.pid;
      }
    if (sender != pid || pid <= 0) {  // another process, or an earlier instance of this service
      ++foreign_;
      continue;
    }
    const NotifyState s = parse_notify(std::string(buf, static_cast<size_t>(n)));
    out.ready = out.ready || s.ready;
    out.watchdog = out.watchdog || s.watchdog;
    out.stopping = out.stopping || s.stopping;
  }
}

}  // namespace gpilot
