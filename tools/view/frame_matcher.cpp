#include "frame_matcher.hpp"

namespace gpilot {

// Messages may come before their frame (UDP gives no order between channels), so they wait in pending_
// until their frame comes, or are dropped as orphans once a newer frame has come without theirs.
FrameMessages* FrameMatcher::slot(int64_t seq, Channel c) {
  seen_ |= c;
  if (any_released_ && seq <= last_released_) {
    ++late_;
    return nullptr;
  }
  Entry& e = pending_[seq];
  e.have |= c;
  return &e.msgs;
}

void FrameMatcher::add_frame(const image_t& image) {
  bool went_back = any_released_ && image.seq <= last_released_;
  for (const auto& [seq, e] : pending_) went_back = went_back || (e.has_image && seq >= image.seq);
  if (went_back) {
    for (auto& f : flush()) restarted_.push_back(std::move(f));
    any_released_ = false;
    frames_added_ = 0;
  }
  ++frames_added_;
  Entry& e = pending_[image.seq];
  e.has_image = true;
  e.image = image;
}

MatchedFrame FrameMatcher::release(std::map<int64_t, Entry>::iterator it) {
  MatchedFrame f;
  f.image = std::move(it->second.image);
  f.msgs = std::move(it->second.msgs);
  f.complete = (it->second.have & seen_) == seen_;
  if (!f.complete) ++incomplete_;
  any_released_ = true;
  last_released_ = it->first;
  pending_.erase(it);
  return f;
}

std::vector<MatchedFrame> FrameMatcher::take_ready() {
  std::vector<MatchedFrame> out(std::make_move_iterator(restarted_.begin()), std::make_move_iterator(restarted_.end()));
  restarted_.clear();
  while (!pending_.empty()) {
    auto it = pending_.begin();
    if (!it->second.has_image) {
      // Messages without a frame: an orphan once a newer frame exists.
      bool newer_frame = false;
      for (auto j = std::next(it); j != pending_.end() && !newer_frame; ++j) newer_frame = j->second.has_image;
      if (!newer_frame) break;
      orphans_ += __builtin_popcount(static_cast<unsigned>(it->second.have));
      pending_.erase(it);
      continue;
    }
    int newer = 0;
    for (auto j = std::next(it); j != pending_.end(); ++j) newer += j->second.has_image ? 1 : 0;
    // The channel set is learnt from the stream: trusted once hold_ frames have passed.
    const bool complete = frames_added_ > hold_ && (it->second.have & seen_) == seen_;
    if ((complete && newer >= 1) || newer >= hold_)
      out.push_back(release(it));
    else
      break;
  }
  return out;
}

std::vector<MatchedFrame> FrameMatcher::flush() {
  std::vector<MatchedFrame> out(std::make_move_iterator(restarted_.begin()), std::make_move_iterator(restarted_.end()));
  restarted_.clear();
  while (!pending_.empty()) {
    auto it = pending_.begin();
    if (it->second.has_image) {
      out.push_back(release(it));
    } else {
      orphans_ += __builtin_popcount(static_cast<unsigned>(it->second.have));
      pending_.erase(it);
    }
  }
  return out;
}

size_t FrameMatcher::pending_frames() const {
  size_t n = 0;
  for (const auto& [seq, e] : pending_) n += e.has_image ? 1 : 0;
  return n;
}

}  // namespace gpilot
