// Pairs each CAMERA frame with the USER_TRACK of the same seq. Either side may arrive first; an item waits
// until its partner comes or until it is `window` seqs older than the newest seq seen, then it is dropped
// and counted. Never pairs different seqs. A seq far below the newest (a restarted source) starts afresh. Pure: no LCM, no clock.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <utility>

namespace gpilot {

template <class Frame, class Track>
class SeqPairer {
 public:
  explicit SeqPairer(int64_t window) : window_(window) {}

  std::optional<std::pair<Frame, Track>> add_frame(int64_t seq, Frame frame) {
    return add(seq, std::move(frame), frames_, tracks_, dropped_frames_, [](Frame& f, Track& t) {
      return std::make_pair(std::move(f), std::move(t));
    });
  }
  std::optional<std::pair<Frame, Track>> add_track(int64_t seq, Track track) {
    return add(seq, std::move(track), tracks_, frames_, dropped_tracks_, [](Track& t, Frame& f) {
      return std::make_pair(std::move(f), std::move(t));
    });
  }

  int64_t dropped_frames() const { return dropped_frames_; }  //!< frames that never met their track
  int64_t dropped_tracks() const { return dropped_tracks_; }  //!< tracks that never met their frame
  size_t waiting() const { return frames_.size() + tracks_.size(); }

 private:
  template <class Mine, class Other, class Make>
  std::optional<std::pair<Frame, Track>> add(int64_t seq, Mine item, std::map<int64_t, Mine>& mine,
                                             std::map<int64_t, Other>& other, int64_t& my_drops, Make make) {
    if (seq < newest_ - kRestartWindows * window_) restart();  // the source started again from a low seq
    if (seq > newest_) newest_ = seq;
    std::optional<std::pair<Frame, Track>> out;
    const auto it = other.find(seq);
    if (it != other.end()) {
      out = make(item, it->second);
      other.erase(it);
    } else if (seq > newest_ - window_) {
      auto [pos, fresh] = mine.insert_or_assign(seq, std::move(item));
      (void)pos;
      if (!fresh) ++my_drops;  // a second item with the same seq replaces the first
    } else {
      ++my_drops;  // already too old to wait for a partner
    }
    expire();
    return out;
  }

  void restart() {
    dropped_frames_ += static_cast<int64_t>(frames_.size());
    dropped_tracks_ += static_cast<int64_t>(tracks_.size());
    frames_.clear();
    tracks_.clear();
    newest_ = INT64_MIN / 2;
  }

  void expire() {
    const int64_t oldest_kept = newest_ - window_;
    while (!frames_.empty() && frames_.begin()->first <= oldest_kept) {
      frames_.erase(frames_.begin());
      ++dropped_frames_;
    }
    while (!tracks_.empty() && tracks_.begin()->first <= oldest_kept) {
      tracks_.erase(tracks_.begin());
      ++dropped_tracks_;
    }
  }

  // A seq more than this many windows below the newest is no late partner (those wait one window): the source
  // started again from a low seq (a restarted capture), and the pairer starts over with it.
  static constexpr int64_t kRestartWindows = 10;
  int64_t window_;
  int64_t newest_ = INT64_MIN / 2;
  std::map<int64_t, Frame> frames_;
  std::map<int64_t, Track> tracks_;
  int64_t dropped_frames_ = 0, dropped_tracks_ = 0;
};

}  // namespace gpilot
