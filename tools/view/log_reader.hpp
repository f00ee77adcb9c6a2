// Reads an LCM log file (the format lcm-logger writes) event by event, and hands each event to a typed
// handler by channel. Written for the tools that work from a whole run's log (gpilot-view --log,
// gpilot-report): a missing or unreadable file is a LogError; a truncated tail ends the read with a
// warning; bytes that are not an event are skipped (resynchronising on the next sync word) and counted;
// a message that does not decode or fails check_message() is counted per channel and skipped.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "message_checks.hpp"

namespace gpilot {

class LogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LogEvent {
  int64_t eventnum = 0;
  int64_t timestamp = 0;  // when the logger received the message, microseconds since the Unix epoch
  std::string channel;
  std::vector<uint8_t> data;
};

class LogReader {
 public:
  // Throws LogError when the file is missing, unreadable, empty, or does not start like an LCM log.
  explicit LogReader(const std::string& path);
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  // The next complete event; false at the end of the log (see warnings() for an early end).
  bool next(LogEvent& ev);

  const std::string& path() const { return path_; }
  int64_t file_size() const { return size_; }
  int64_t position() const { return pos_; }
  int64_t events_read() const { return events_; }
  int64_t bytes_skipped() const { return skipped_; }
  // Why the log was not read cleanly to its end (truncated tail, corrupt stretches); empty if it was.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  bool read_exact(void* dst, size_t n);
  bool find_sync();  // advances to just after the next sync word; counts what it skipped

  std::string path_;
  std::FILE* f_ = nullptr;
  int64_t size_ = 0;
  int64_t pos_ = 0;
  int64_t events_ = 0;
  int64_t skipped_ = 0;
  std::vector<std::string> warnings_;
};

// Decodes events into typed messages for the handlers registered per channel.
class LogDispatcher {
 public:
  template <class Msg>
  void on(const std::string& channel, std::function<void(const Msg&, int64_t)> handler) {
    handlers_[channel] = [this, channel, handler](const LogEvent& ev) {
      Msg msg;
      if (msg.decode(ev.data.data(), 0, static_cast<int>(ev.data.size())) < 0) {
        reject(channel, std::to_string(ev.data.size()) + " bytes do not decode as " + Msg::getTypeName());
        return;
      }
      const std::string why = check_message(msg);
      if (!why.empty()) {
        reject(channel, why);
        return;
      }
      handler(msg, ev.timestamp);
    };
  }

  // Runs the channel's handler; events on channels nobody asked for are counted and ignored.
  void dispatch(const LogEvent& ev);

  int64_t rejected_total() const { return rejected_total_; }
  const std::map<std::string, int64_t>& rejected_by_channel() const { return rejected_; }
  const std::string& last_reject_reason() const { return last_reason_; }
  int64_t ignored() const { return ignored_; }

 private:
  void reject(const std::string& channel, const std::string& why);

  std::map<std::string, std::function<void(const LogEvent&)>> handlers_;
  std::map<std::string, int64_t> rejected_;
  int64_t rejected_total_ = 0;
  int64_t ignored_ = 0;
  std::string last_reason_;
};

// Prints "<tool>: <what> <pct>% of <file>" on stderr at most every period_s seconds of wall time.
class Progress {
 public:
  Progress(std::string tool, double period_s = 2.0);
  void update(const LogReader& log, const std::string& what);

 private:
  std::string tool_;
  int64_t period_us_;
  int64_t next_us_;
};

}  // namespace gpilot
