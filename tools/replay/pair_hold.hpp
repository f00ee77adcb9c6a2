// The order gpilot-replay gives a pairing stage its two inputs. The live hands stage pairs CAMERA and
// USER_TRACK by seq (SeqPairer) and works a pair when its second half arrives; an unpaired half expires once
// one 15 seqs newer has come (hands.match_window). Which half came first, and how far one stream ran ahead of
// the other, depended on how each socket's queue drained inside the hands process, which no log records: the
// recorder hears both sockets itself, and on a loaded machine it timestamps a frame after the track made from
// it, or a track 15 frames after its frame. Given in the log's order, such a frame expired in the replay, or
// was given after its track had expired, although the live stage had paired it: a HAND_OBS not replayed and
// every later one different (the skin model learns from each pair). So each half is held until the other is
// in, and the pair is given then, `first`'s half first. Pairs complete in seq order (each stream is in order
// in the log), live and here, so the stage works the same pairs in the same order; a half that never meets
// its partner (the live stage skipped that frame, or the tracker did) is never given: alone it gives nothing.
// Pure: no LCM, no clock.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gpilot {

class PairHold {
 public:
  struct Message {
    std::string channel;
    int64_t timestamp;
    std::vector<uint8_t> bytes;
  };

  PairHold(std::string first, std::string second) : first_(std::move(first)), second_(std::move(second)) {}

  bool pairs(const std::string& channel) const { return channel == first_ || channel == second_; }

  // Holds the message; when its partner is already held, returns the pair (`first`'s message first) and drops
  // the halves older than it (within kStreamWindow: not a restarted source's low seqs), which will never pair.
  std::vector<Message> add(const std::string& channel, int64_t seq, int64_t timestamp, std::vector<uint8_t> bytes) {
    const bool is_first = channel == first_;
    auto& mine = is_first ? firsts_ : seconds_;
    auto& other = is_first ? seconds_ : firsts_;
    const auto partner = other.find(seq);
    if (partner == other.end()) {
      mine.insert_or_assign(seq, Message{channel, timestamp, std::move(bytes)});
      for (auto* held : {&firsts_, &seconds_})
        while (held->size() > kMaxWaiting) held->erase(held->begin()), ++never_paired_;
      return {};
    }
    std::vector<Message> pair;
    Message own{channel, timestamp, std::move(bytes)};
    if (is_first) {
      pair.push_back(std::move(own));
      pair.push_back(std::move(partner->second));
    } else {
      pair.push_back(std::move(partner->second));
      pair.push_back(std::move(own));
    }
    other.erase(partner);
    for (auto* held : {&firsts_, &seconds_})
      for (auto old = held->lower_bound(seq - kStreamWindow); old != held->end() && old->first < seq;)
        old = held->erase(old), ++never_paired_;
    return pair;
  }
  size_t waiting() const { return firsts_.size() + seconds_.size(); }
  int64_t never_paired() const { return never_paired_; }

 private:
  static constexpr size_t kMaxWaiting = 1000;
  static constexpr int64_t kStreamWindow = 1000;
  std::string first_, second_;
  std::map<int64_t, Message> firsts_, seconds_;
  int64_t never_paired_ = 0;
};

}  // namespace gpilot
