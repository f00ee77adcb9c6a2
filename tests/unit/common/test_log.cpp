// The logging facility: one line format ("<process>: <level>: <message>"), levels filtered, names parsed,
// and every process gives --version and --log-level through ServiceCli.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "log.hpp"
#include "run_command.hpp"
#include "service_cli.hpp"

namespace gpilot {
namespace {

// Runs f with stderr sent to a file; returns what was written.
std::string stderr_of(const std::function<void()>& f) {
  char path[] = "/tmp/gpilot_test_log_XXXXXX";
  const int fd = mkstemp(path);
  EXPECT_GE(fd, 0);
  std::fflush(stderr);
  const int saved = dup(2);
  dup2(fd, 2);
  f();
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  close(fd);
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  unlink(path);
  return ss.str();
}

TEST(Log, OneLineFormatAndLevels) {
  set_log_name("gpilot-test");
  set_log_level(LogLevel::kInfo);
  EXPECT_EQ(stderr_of([] {
              log_error("bad %d", 1);
              log_warn("careful");
              log_info("source back: %s", "camera");
              log_debug("not shown at info");
            }),
            "gpilot-test: error: bad 1\ngpilot-test: warn: careful\ngpilot-test: info: source back: camera\n");
  set_log_level(LogLevel::kWarn);
  EXPECT_EQ(stderr_of([] { log_info("hidden"); log_warn("shown\n"); }), "gpilot-test: warn: shown\n");
  set_log_level(LogLevel::kDebug);
  EXPECT_EQ(stderr_of([] { log_debug("x=%.1f", 0.5); }), "gpilot-test: debug: x=0.5\n");
  set_log_level(LogLevel::kInfo);
}

TEST(Log, LevelNamesAndEnvironment) {
  EXPECT_EQ(parse_log_level("debug"), LogLevel::kDebug);
  EXPECT_EQ(parse_log_level("warn"), LogLevel::kWarn);
  EXPECT_FALSE(parse_log_level("WARN").has_value());
  EXPECT_FALSE(parse_log_level("verbose").has_value());
  setenv("GPILOT_LOG_LEVEL", "error", 1);
  EXPECT_TRUE(set_log_level_from_env());
  EXPECT_EQ(log_level(), LogLevel::kError);
  setenv("GPILOT_LOG_LEVEL", "loud", 1);
  EXPECT_FALSE(set_log_level_from_env());
  EXPECT_EQ(log_level(), LogLevel::kError);  // unchanged
  unsetenv("GPILOT_LOG_LEVEL");
  set_log_level(LogLevel::kInfo);
}

test::CommandOutput run_config(const std::string& args) {
  return test::run_command(std::string(GPILOT_BIN_DIR) + "/gpilot-config " + args + " 2>&1");
}

TEST(Log, ProcessesShareTheFormatVersionAndLevelFlags) {
  // --version: the program's name and the build's git describe (or the project version without git)
  const test::CommandOutput v = run_config("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_EQ(v.out, std::string("gpilot-config ") + gpilot_version() + "\n");
  EXPECT_NE(std::string(gpilot_version()), "");
  // a config error is an error line naming the key
  const test::CommandOutput bad = run_config("--set flight.backend=simm");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(bad.out, "gpilot-config: error: config error: flight.backend: 'simm' is not one of sim, mavlink, none\n");
  // --log-level and GPILOT_LOG_LEVEL must name a level
  EXPECT_EQ(run_config("--log-level debug --defaults").code, 0);
  EXPECT_EQ(run_config("--log-level loud --defaults").code, 2);
  EXPECT_EQ(run_config("--defaults").code, 0);
  setenv("GPILOT_LOG_LEVEL", "loud", 1);
  const test::CommandOutput env = run_config("--defaults");
  unsetenv("GPILOT_LOG_LEVEL");
  EXPECT_EQ(env.code, 2);
  EXPECT_NE(env.out.find("GPILOT_LOG_LEVEL='loud'"), std::string::npos) << env.out;
}

}  // namespace
}  // namespace gpilot
