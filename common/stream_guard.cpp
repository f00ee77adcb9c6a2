#include "stream_guard.hpp"

#include <iterator>

namespace gpilot {
namespace {

std::string ms(int64_t us) { return std::to_string(us / 1000) + " ms"; }

}  // namespace

std::string StreamGuard::admit(const std::string& stream, int64_t utime, int64_t seq, int64_t arrival_utime) {
  if (seq < -1 || seq > kMaxSeq) return "seq " + std::to_string(seq) + " is outside [-1, 2^53]";
  if (utime < arrival_utime - window_us_)
    return "utime " + ms(arrival_utime - utime) + " before its arrival (outside bus.time_window_s: stale or replayed)";
  if (utime > arrival_utime + window_us_)
    return "utime " + ms(utime - arrival_utime) + " after its arrival (outside bus.time_window_s: a clock far off)";
  auto it = last_.find(stream);
  if (it != last_.end()) {
    const Last& last = it->second;
    if (utime < last.utime)
      return "utime " + ms(last.utime - utime) + " older than this stream's newest (reordered or replayed)";
    if (utime == last.utime && seq <= last.seq) return "seq " + std::to_string(seq) + " again (a duplicate)";
  } else if (last_.size() >= kMaxStreams) {
    for (auto i = last_.begin(); i != last_.end();)  // streams silent for longer than the window
      i = i->second.utime < arrival_utime - window_us_ ? last_.erase(i) : std::next(i);
    if (last_.size() >= kMaxStreams) return "too many streams within the time window";
  }
  last_[stream] = Last{utime, seq};
  return "";
}

}  // namespace gpilot
