// gpilot-launch's side of systemd's notify protocol (sd_notify(3)), so that a stage runs the same sd_notify
// code under systemd and under ./deploy/run: one unix datagram socket per watched service, in the abstract
// namespace ("@gpilot-launch-<launcher pid>-<service>": nothing on disk to clean up, private to the network
// namespace), handed to the child as NOTIFY_SOCKET with WATCHDOG_USEC. Only the child's own datagrams count:
// the kernel attaches the sender's pid (SO_PASSCRED), so another process cannot keep a frozen stage "alive".
#pragma once

#include <cstdint>
#include <string>
#include <sys/types.h>

namespace gpilot {

// What one or more notify datagrams said (newline-separated KEY=VALUE assignments, as sd_notify sends them).
struct NotifyState {
  bool ready = false;     //!< READY=1
  bool watchdog = false;  //!< WATCHDOG=1
  bool stopping = false;  //!< STOPPING=1
  bool any() const { return ready || watchdog || stopping; }
};
NotifyState parse_notify(const std::string& text);

class NotifySocket {
 public:
  // Binds the abstract address "gpilot-launch-<getpid()>-<name>". Throws std::runtime_error when it cannot.
  explicit NotifySocket(const std::string& name);
  ~NotifySocket();
  NotifySocket(const NotifySocket&) = delete;
  NotifySocket& operator=(const NotifySocket&) = delete;

  // The value for NOTIFY_SOCKET ('@' stands for the abstract namespace's leading NUL).
  const std::string& address() const { return address_; }
  // Reads every waiting datagram without blocking: what those sent by `pid` said. Others are counted.
  NotifyState poll(pid_t pid);
  int64_t foreign() const { return foreign_; }

 private:
  int fd_ = -1;
  std::string address_;
  int64_t foreign_ = 0;
};

}  // namespace gpilot
