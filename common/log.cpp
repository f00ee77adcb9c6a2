#include "log.hpp"

#include <atomic>
#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace gpilot {
namespace {

std::atomic<int> g_level{static_cast<int>(LogLevel::kInfo)};
std::mutex g_name_mutex;
std::string& name_storage() {
  static std::string name = program_invocation_short_name;  // glibc: argv[0] without its directory
  return name;
}

void vlog(LogLevel level, const char* format, va_list args) {
  if (!log_enabled(level)) return;
  char body[2048];
  std::vsnprintf(body, sizeof body, format, args);  // longer messages are cut, never a second write
  std::string name;
  {
    std::lock_guard<std::mutex> lock(g_name_mutex);
    name = name_storage();
  }
  std::string line = name + ": " + log_level_name(level) + ": " + body;
  if (line.empty() || line.back() != '\n') line += '\n';
  std::fwrite(line.data(), 1, line.size(), stderr);
  std::fflush(stderr);
}

}  // namespace

std::optional<LogLevel> parse_log_level(const std::string& text) {
  for (LogLevel l : {LogLevel::kError, LogLevel::kWarn, LogLevel::kInfo, LogLevel::kDebug})
    if (text == log_level_name(l)) return l;
  return std::nullopt;
}

const char* log_level_name(LogLevel level) {
  switch (level) {
    case LogLevel::kError: return "error";
    case LogLevel::kWarn: return "warn";
    case LogLevel::kInfo: return "info";
    case LogLevel::kDebug: return "debug";
  }
  return "?";
}

void set_log_name(const std::string& name) {
  std::lock_guard<std::mutex> lock(g_name_mutex);
  name_storage() = name;
}

void set_log_level(LogLevel level) { g_level = static_cast<int>(level); }
LogLevel log_level() { return static_cast<LogLevel>(g_level.load()); }

bool set_log_level_from_env() {
  const char* env = std::getenv("GPILOT_LOG_LEVEL");
  if (!env || !*env) return true;
  const auto level = parse_log_level(env);
  if (!level) return false;
  set_log_level(*level);
  return true;
}

void log_message(LogLevel level, const char* format, ...) {
  va_list args;
  va_start(args, format);
  vlog(level, format, args);
  va_end(args);
}

#define GPILOT_LOG_AT(fn, level)          \
  void fn(const char* format, ...) {      \
    va_list args;                         \
    va_start(args, format);               \
    vlog(level, format, args);            \
    va_end(args);                         \
  }
GPILOT_LOG_AT(log_error, LogLevel::kError)
GPILOT_LOG_AT(log_warn, LogLevel::kWarn)
GPILOT_LOG_AT(log_info, LogLevel::kInfo)
GPILOT_LOG_AT(log_debug, LogLevel::kDebug)
#undef GPILOT_LOG_AT

}  // namespace gpilot
