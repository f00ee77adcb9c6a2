// Per-stream order and freshness of bus messages (no clock inside: arrival times come in). A stream is one
// publisher's messages on one channel. Rules, each a counted rejection with its reason:
//  - utime within time_window of the arrival (a message from an hour ago, or from the future, is not news);
//  - utime not older than the stream's newest, and not the same message again (same seq and utime);
//  - seq in [-1, kMaxSeq] (-1: "none yet", as FLIGHT_SETPOINT says; seq + 1 must never overflow downstream).
// seq may go back when utime moves on: the publisher restarted (a new process counts from 0) and its new
// stream is accepted at once.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>

namespace gpilot {

class StreamGuard {
 public:
  static constexpr int64_t kMaxSeq = int64_t{1} << 53;

  explicit StreamGuard(int64_t window_us) : window_us_(window_us) {}
  // "" when the message may pass (and it becomes the stream's newest), else why not.
  std::string admit(const std::string& stream, int64_t utime, int64_t seq, int64_t arrival_utime);
  size_t streams() const { return last_.size(); }

 private:
  struct Last {
    int64_t utime, seq;
  };
  static constexpr size_t kMaxStreams = 1024;  // made-up stream names cannot grow the table without bound
  int64_t window_us_;
  std::unordered_map<std::string, Last> last_;
};

}  // namespace gpilot
