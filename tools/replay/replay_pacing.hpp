// Which recorded inputs gpilot-replay gives a stage. A live stage reads CAMERA through a bounded queue
// (tracker.camera_queue): when it falls behind (a loaded machine) it skips the oldest frames, and a replay that
// gave it every frame would follow another track from the first skipped frame on. Each skipped frame left one
// trace: the stage published no output of its seq (the tracker one USER_TRACK per processed frame, hands one
// HAND_OBS per processed pair, each with the frame's seq). So an input of a paced channel is given only when
// the log records an output of the same seq on the rule's output channel; a log that records none of that
// channel at all (a camera-only log) is not paced. With several rules on one input (a chain), the input is
// given when any rule wants it.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace gpilot {

class ReplayPacing {
 public:
  // Input messages on `input` are given only for seqs the log records on `output`.
  void add_rule(const std::string& input, const std::string& output) { rules_[input].push_back(output); }
  // The pre-scan of the log: one recorded message on channel, of seq.
  void recorded(const std::string& channel, int64_t seq) { seqs_[channel].insert(seq); }
  // Whether the stage gets this input message (counts the ones held back).
  bool give(const std::string& channel, int64_t seq) {
    const auto r = rules_.find(channel);
    if (r == rules_.end()) return true;
    for (const auto& output : r->second) {
      const auto s = seqs_.find(output);
      if (s == seqs_.end() || s->second.count(seq)) return true;
    }
    ++held_back_;
    return false;
  }
  // Every output channel some rule reads (what the pre-scan must record).
  std::set<std::string> output_channels() const {
    std::set<std::string> out;
    for (const auto& [input, outputs] : rules_) out.insert(outputs.begin(), outputs.end());
    return out;
  }
  int64_t held_back() const { return held_back_; }

 private:
  std::map<std::string, std::vector<std::string>> rules_;
  std::map<std::string, std::set<int64_t>> seqs_;
  int64_t held_back_ = 0;
};

}  // namespace gpilot
