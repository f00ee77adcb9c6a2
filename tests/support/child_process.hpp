// A program run as a child process by a test, signalled and reaped: the tests that run services, tools,
// loggers and gpilot-launch as real processes share this one instead of each spawning, killing and waiting
// in its own words. A child still running when its object goes away is stopped with SIGTERM and reaped, so
// a failing test leaves no process behind.
#pragma once

#include <cerrno>
#include <csignal>
#include <string>
#include <utility>
#include <vector>

#include <spawn.h>
#include <sys/types.h>
#include <sys/wait.h>

extern char** environ;

namespace gpilot::test {

class ChildProcess {
 public:
  // Starts argv[0] with argv, in this process's environment; a name without '/' is looked up on PATH (as
  // execvp does). pid() is -1 when it could not be started.
  explicit ChildProcess(std::vector<std::string> argv) {
    if (argv.empty()) return;
    std::vector<char*> args;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    if (posix_spawnp(&pid_, args[0], nullptr, nullptr, args.data(), environ) != 0) pid_ = -1;
  }
  ~ChildProcess() { stop(); }

  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ChildProcess(ChildProcess&& other) noexcept { take(other); }
  ChildProcess& operator=(ChildProcess&& other) noexcept {
    if (this != &other) {
      stop();
      take(other);
    }
    return *this;
  }

  pid_t pid() const { return pid_; }
  // Started and not yet ended (an ended child is reaped here, its status kept for stop() and wait()).
  bool running() { return pid_ > 0 && !reap(WNOHANG); }
  // Sends signal unless the child has already been reaped, waits for it to end; its wait status (-1 when it
  // never started). Again later: the same status, nothing sent.
  int stop(int signal = SIGTERM) {
    if (pid_ > 0 && !reaped_) {
      kill(pid_, signal);
      reap(0);
    }
    return status_;
  }
  // Waits for the child to end by itself; its wait status (-1 when it never started).
  int wait() {
    reap(0);
    return status_;
  }

 private:
  // Collects the status of an ended child (blocking unless options has WNOHANG); true once collected.
  bool reap(int options) {
    if (pid_ <= 0 || reaped_) return true;
    int status = 0;
    pid_t got;
    do got = waitpid(pid_, &status, options);
    while (got == -1 && errno == EINTR);
    if (got == 0) return false;
    status_ = got == pid_ ? status : -1;
    reaped_ = true;
    return true;
  }
  void take(ChildProcess& other) {
    pid_ = std::exchange(other.pid_, -1);
    reaped_ = std::exchange(other.reaped_, false);
    status_ = std::exchange(other.status_, -1);
  }

  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = -1;
};

}  // namespace gpilot::test
