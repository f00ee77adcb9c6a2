// The order gpilot-replay gives a pairing stage its two inputs. The live hands stage pairs CAMERA and
// USER_TRACK by seq (SeqPairer) and works a pair when its second half arrives; an unpaired frame expires once
// frames 15 seqs newer have come (hands.match_window). How far one stream ran ahead of the other depended on
// how each socket's queue drained inside the hands process, which no log records: the recorder hears both
// sockets itself. Given in the log's order, a frame whose track came 15 frames later (the tracker behind
// under load) expired in the replay although the live stage had paired it: one HAND_OBS not replayed and
// every later one different (the skin model learns from each pair). So a frame is held until its partner
// is given, and then given just before it: the stage works the same pairs in the same order as live.
// Pure: no LCM, no clock.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gpilot {

class PairHold {
 public:
  struct Held {
    int64_t timestamp;
    std::vector<uint8_t> bytes;
  };

  // Messages on `held` wait for the message of the same seq on `partner`.
  PairHold(std::string held, std::string partner) : held_(std::move(held)), partner_(std::move(partner)) {}

  const std::string& held_channel() const { return held_; }
  bool holds(const std::string& channel) const { return channel == held_; }
  bool is_partner(const std::string& channel) const { return channel == partner_; }

  void hold(int64_t seq, int64_t timestamp, std::vector<uint8_t> bytes) {
    waiting_.insert_or_assign(seq, Held{timestamp, std::move(bytes)});
    while (waiting_.size() > kMaxWaiting) waiting_.erase(waiting_.begin()), ++never_paired_;
  }
  // The partner of `seq` is about to be given: the held message of that seq, if one waits. Partners come in
  // seq order, so a held message a little older than seq (within kStreamWindow: not one of a restarted
  // source's low seqs) will never meet its partner (the live stage skipped that frame's track) and goes.
  std::optional<Held> release(int64_t seq) {
    std::optional<Held> out;
    const auto it = waiting_.find(seq);
    if (it != waiting_.end()) {
      out = std::move(it->second);
      waiting_.erase(it);
    }
    for (auto old = waiting_.lower_bound(seq - kStreamWindow); old != waiting_.end() && old->first < seq;) {
      old = waiting_.erase(old);
      ++never_paired_;
    }
    return out;
  }
  size_t waiting() const { return waiting_.size(); }
  int64_t never_paired() const { return never_paired_; }

 private:
  static constexpr size_t kMaxWaiting = 1000;
  static constexpr int64_t kStreamWindow = 1000;
  std::string held_, partner_;
  std::map<int64_t, Held> waiting_;
  int64_t never_paired_ = 0;
};

}  // namespace gpilot
