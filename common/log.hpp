// One logging facility for every gpilot process: four levels and one line format on stderr,
//   <process>: <level>: <message>        e.g. "gpilot-capture: info: source back: synthetic scenario 'tour'"
// (journald and ./deploy/run's log files add the time). The level is chosen by --log-level (ServiceCli) or
// $GPILOT_LOG_LEVEL (error, warn, info, debug; default info); lines below it cost one comparison.
// Progress counters that redraw one line ("\r12/50 images") are not log lines and stay plain stderr.
#pragma once

#include <optional>
#include <string>

namespace gpilot {

enum class LogLevel { kError = 0, kWarn = 1, kInfo = 2, kDebug = 3 };

// "error", "warn", "info", "debug" -> level; anything else -> nullopt.
std::optional<LogLevel> parse_log_level(const std::string& text);
const char* log_level_name(LogLevel level);

// The process name at the start of each line (default: the program's name) and the lowest level written.
void set_log_name(const std::string& name);
void set_log_level(LogLevel level);
LogLevel log_level();
inline bool log_enabled(LogLevel level) { return static_cast<int>(level) <= static_cast<int>(log_level()); }

// Sets the level from $GPILOT_LOG_LEVEL when it is set; returns false (level unchanged) when it names no level.
bool set_log_level_from_env();

// printf-style, checked by the compiler; one write per line, so lines of concurrent threads do not interleave.
void log_message(LogLevel level, const char* format, ...) __attribute__((format(printf, 2, 3)));
void log_error(const char* format, ...) __attribute__((format(printf, 1, 2)));
void log_warn(const char* format, ...) __attribute__((format(printf, 1, 2)));
void log_info(const char* format, ...) __attribute__((format(printf, 1, 2)));
void log_debug(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace gpilot
