// A shell command run to its end by a test: its exit status and what it wrote on stdout (add 2>&1 to the
// command for stderr too). For programs expected to end by themselves (a refused config, --version); a
// service under test runs as a ChildProcess (child_process.hpp).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace gpilot::test {

struct CommandOutput {
  int code;  // exit status; -1 when the command could not run or did not exit normally
  std::string out;
};

inline CommandOutput run_command(const std::string& command) {
  FILE* p = popen(command.c_str(), "r");
  if (!p) return {-1, ""};
  std::string out;
  char buf[512];
  for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace gpilot::test
