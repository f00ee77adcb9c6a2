// The recorder's reordering: events from two sockets (the bus and the frames URL, each with its own LCM
// receive thread) are dispatched in the order their sockets were polled, not always in the order they arrived.
// Held for a moment, they are written in arrival order (receive time, then dispatch order for equal times), so
// the log reads as one bus's would. Pure: no LCM, no clock.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gpilot {

class EventOrder {
 public:
  struct Event {
    int64_t utime;
    std::string channel;
    std::vector<uint8_t> data;
  };

  void add(int64_t utime, const std::string& channel, const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    held_.emplace(std::make_pair(utime, next_++), Event{utime, channel, std::vector<uint8_t>(p, p + size)});
  }
  // fn(event) for every event received before utime (all of them with INT64_MAX), in arrival order.
  template <class Fn>
  void release_before(int64_t utime, Fn&& fn) {
    while (!held_.empty() && held_.begin()->first.first < utime) {
      fn(held_.begin()->second);
      held_.erase(held_.begin());
    }
  }
  size_t held() const { return held_.size(); }

 private:
  std::map<std::pair<int64_t, uint64_t>, Event> held_;
  uint64_t next_ = 0;
};

}  // namespace gpilot
