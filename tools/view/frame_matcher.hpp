// Puts each CAMERA frame together with the per-frame messages of the same seq (USER_TRACK, HAND_OBS,
// GESTURE_CMD, GROUND_TRUTH), so the overlay is drawn on the frame it belongs to.
//
// How frames are released, oldest first and never out of order:
// - complete: every per-frame channel seen in the stream has delivered this frame's seq, and a newer
//   frame has arrived. The channel set is learnt from the stream, so this rule starts only after the
//   first hold_frames frames (a slow stage's first message can come frames after the first frame);
// - or held: hold_frames newer frames have arrived, whatever is still missing (a stage is slow or down);
// - or flushed: end of log or shutdown.
// A message for a frame already released is late: counted and dropped. A CAMERA seq that goes back (the
// source restarted) releases everything pending first.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "gpilot/image_t.hpp"
#include "overlay.hpp"

namespace gpilot {

struct MatchedFrame {
  image_t image;
  FrameMessages msgs;
  bool complete = false;  // false: released by hold or flush with something missing
};

class FrameMatcher {
 public:
  explicit FrameMatcher(int hold_frames = 3) : hold_(hold_frames < 1 ? 1 : hold_frames) {}

  void add_frame(const image_t& image);
  void add(const user_track_t& m) {
    if (auto* s = slot(m.seq, kTrack)) s->track = m;
  }
  void add(const hand_obs_t& m) {
    if (auto* s = slot(m.seq, kHand)) s->hand = m;
  }
  void add(const gesture_cmd_t& m) {
    if (auto* s = slot(m.seq, kCmd)) s->cmd = m;
  }
  void add(const ground_truth_t& m) {
    if (auto* s = slot(m.seq, kTruth)) s->truth = m;
  }

  // Frames ready to draw, oldest first.
  std::vector<MatchedFrame> take_ready();
  // Everything with a frame, oldest first (end of input).
  std::vector<MatchedFrame> flush();

  int64_t late_messages() const { return late_; }      // arrived after their frame was released
  int64_t orphan_messages() const { return orphans_; }  // their frame never came
  int64_t incomplete_frames() const { return incomplete_; }
  size_t pending_frames() const;

 private:
  enum Channel { kTrack = 1, kHand = 2, kCmd = 4, kTruth = 8 };
  struct Entry {
    bool has_image = false;
    image_t image;
    FrameMessages msgs;
    int have = 0;  // Channel bits delivered
  };
  FrameMessages* slot(int64_t seq, Channel c);  // nullptr (counted late) when the frame is already out
  MatchedFrame release(std::map<int64_t, Entry>::iterator it);

  int hold_;
  int seen_ = 0;  // Channel bits seen in the stream so far
  int64_t frames_added_ = 0;  // since the start or a restart
  std::map<int64_t, Entry> pending_;
  std::deque<MatchedFrame> restarted_;  // released by a seq restart, handed out by the next take_ready
  bool any_released_ = false;
  int64_t last_released_ = 0;
  int64_t late_ = 0, orphans_ = 0, incomplete_ = 0;
};

}  // namespace gpilot
