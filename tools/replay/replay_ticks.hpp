// When a timer-driven stage (gpilot-flight) ticked in the live run, and which inputs it had then. Live, the
// stage's timer fires on its own clock between arrivals, and each output it publishes then is stamped with that
// instant (utime) and names the newest input of each keyed channel it was computed from (FLIGHT_SETPOINT:
// latest_command_seq, track_utime, control_utime). The logger writes what was sent in the order it was sent, so every input
// a tick had is logged before that tick's output; but an input sent just before a tick that the stage had not
// yet dispatched is logged before the output too, and was not used. So a logged input of a keyed channel is
// held back until the first recorded output that names it (or a later input of its channel), and the stage's
// timer is fired at each recorded output's own utime (BusNode::run_timers_at). Other inputs (the vehicle
// states the flight process publishes itself, in the order it logged them) go in log order. A held input the
// ticks never name again (a repeat of an operator request already named) is not delivered: it changed nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gpilot {

class ReplayTicks {
 public:
  using Bytes = std::vector<uint8_t>;
  // A recorded output: the tick's instant and the key of the newest input of each keyed channel it names
  // (false when the bytes are not the output message).
  using ReadOutput = std::function<bool(const Bytes&, int64_t* utime, std::map<std::string, int64_t>* keys)>;
  using KeyOf = std::function<int64_t(const Bytes&)>;

  // keyed: each keyed input channel's key; none: the key an output names when it had no input of that channel.
  ReplayTicks(std::string output, ReadOutput read, std::map<std::string, KeyOf> keyed, std::map<std::string, int64_t> none)
      : output_(std::move(output)), read_(std::move(read)), keyed_(std::move(keyed)), none_(std::move(none)) {}

  const std::string& output() const { return output_; }
  bool keyed(const std::string& channel) const { return keyed_.count(channel) > 0; }

  // A logged input of a keyed channel, held until a tick names it.
  void hold(const std::string& channel, int64_t log_time, Bytes bytes) {
    const int64_t key = keyed_.at(channel)(bytes);
    held_[channel].push_back(Held{log_time, key, std::move(bytes)});
  }

  // A recorded output: deliver(channel, log_time, bytes) for every held input the tick had, in log order;
  // returns the tick's utime, or -1 when the output does not read.
  int64_t tick(const Bytes& output,
               const std::function<void(const std::string&, int64_t, const Bytes&)>& deliver) {
    int64_t utime = -1;
    std::map<std::string, int64_t> keys;
    if (!read_(output, &utime, &keys)) return -1;
    for (auto& [channel, queue] : held_) {
      const auto k = keys.find(channel);
      if (k == keys.end()) continue;
      size_t upto = 0;  // deliver the first `upto` held inputs: up to and including the one the tick names
      while (upto < queue.size() && queue[upto].key != k->second) ++upto;
      if (upto == queue.size()) {  // named input already delivered, or not in the log (the logger lost it)
        const auto last = delivered_.find(channel);
        if (k->second != none_.at(channel) && (last == delivered_.end() || last->second != k->second)) ++not_logged_;
        continue;
      }
      for (size_t i = 0; i <= upto; ++i) deliver(channel, queue[i].log_time, queue[i].bytes);
      delivered_[channel] = k->second;
      queue.erase(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(upto) + 1);
    }
    return utime;
  }

  // Ticks that named an input the log does not hold (lost by the logger: that tick cannot replay exactly).
  int64_t not_logged() const { return not_logged_; }

  // Inputs still held (logged after the last tick that could name them).
  size_t held() const {
    size_t n = 0;
    for (const auto& [channel, queue] : held_) n += queue.size();
    return n;
  }

 private:
  struct Held {
    int64_t log_time;
    int64_t key;
    Bytes bytes;
  };
  std::string output_;
  ReadOutput read_;
  std::map<std::string, KeyOf> keyed_;
  std::map<std::string, int64_t> none_;
  std::map<std::string, std::deque<Held>> held_;
  std::map<std::string, int64_t> delivered_;  // per channel, the key of the last input delivered
  int64_t not_logged_ = 0;
};

}  // namespace gpilot
