// Which frame gpilot-replay gives a manual TRACKER_INIT box before. The live tracker starts the box on the next
// frame it processes after the message arrives (a click in gpilot-view, gpilot-ctl); which frame that was
// depended on when the message reached the tracker process, which no log records: the recorder hears the bus
// and the frames' URL on sockets of their own, and may write the init a few frames before or after the frame
// it took effect on. Given in the log's order, the replay started the track on another frame, and every box
// after it differed. The live stage left one trace: the USER_TRACK that starts a manual track (a new track_id,
// init_source MANUAL) carries the box, cut to the frame. So each SET_BOX is matched, from a pre-scan of the
// log, to the manual start of its box nearest the frame it was logged after, and given just before that
// frame. An init with no such start (refused, or replaced by another before a frame came) is given where the
// log has it. A RESET drops the track on the next frame: a USER_TRACK that is not TRACKING, or tracks a new
// track_id, right after one that was TRACKING (the tracker itself leaves TRACKING only through LOST); each is
// matched to the nearest such drop within a few frames, and one that dropped nothing visible (the track was
// LOST or searching already) is given where the log has it. Pure: no LCM, no clock.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <vector>

namespace gpilot {

class InitAlign {
 public:
  struct Box {
    double x = 0, y = 0, w = 0, h = 0;
  };

  // The pre-scan, in log order.
  void frame(int64_t seq) { last_frame_ = seq; }
  void manual_start(int64_t seq, Box box) { starts_.push_back({seq, box, true}); }
  void dropped(int64_t seq) { starts_.push_back({seq, {}, false}); }
  // The next TRACKER_INIT of the log: its index is its order among them.
  void set_box(Box box) { inits_.push_back({last_frame_, box, true}); }
  void reset() { inits_.push_back({last_frame_, {}, false}); }
  // Matches the inits to the starts and drops; call once after the pre-scan.
  void finish() {
    std::vector<bool> used(starts_.size(), false);
    for (size_t i = 0; i < inits_.size(); ++i) {
      const Init& in = inits_[i];
      int best = -1;
      int64_t best_distance = (in.set_box ? kWindow : kResetWindow) + 1;
      for (size_t k = 0; k < starts_.size(); ++k) {
        if (used[k] || starts_[k].manual != in.set_box) continue;
        if (in.set_box && overlap(starts_[k].box, in.box) < kMinOverlap) continue;
        const int64_t distance = std::llabs(starts_[k].seq - (in.logged_after + 1));
        if (distance < best_distance) best = static_cast<int>(k), best_distance = distance;
      }
      if (best < 0) continue;
      used[static_cast<size_t>(best)] = true;
      frame_of_[i] = starts_[static_cast<size_t>(best)].seq;
      due_[starts_[static_cast<size_t>(best)].seq].push_back(i);
    }
  }
  // The frame the index-th init is given before, or none (given where the log has it).
  std::optional<int64_t> frame_of(size_t index) const {
    const auto it = frame_of_.find(index);
    if (it == frame_of_.end()) return std::nullopt;
    return it->second;
  }
  // The init indices due just before frame seq.
  const std::vector<size_t>& due_before(int64_t seq) const {
    static const std::vector<size_t> none;
    const auto it = due_.find(seq);
    return it == due_.end() ? none : it->second;
  }

 private:
  // The part of the init's box inside the frame is the start's box: the start's area inside the init's box,
  // over the start's area (1 for the box itself).
  static double overlap(const Box& start, const Box& init) {
    const double x0 = std::max(start.x, init.x), y0 = std::max(start.y, init.y);
    const double x1 = std::min(start.x + start.w, init.x + init.w), y1 = std::min(start.y + start.h, init.y + init.h);
    const double area = start.w * start.h;
    return x1 > x0 && y1 > y0 && area > 0 ? (x1 - x0) * (y1 - y0) / area : 0.0;
  }
  struct Start {
    int64_t seq;
    Box box;
    bool manual;  // a manual start; else a drop
  };
  struct Init {
    int64_t logged_after;
    Box box;
    bool set_box;  // else a RESET
  };
  static constexpr int64_t kWindow = 50;        // frames between where the log has the init and its start
  static constexpr int64_t kResetWindow = 10;   // a drop is less distinct than a box: nearer
  static constexpr double kMinOverlap = 0.95;
  int64_t last_frame_ = -1;
  std::vector<Start> starts_;
  std::vector<Init> inits_;
  std::map<size_t, int64_t> frame_of_;
  std::map<int64_t, std::vector<size_t>> due_;
};

}  // namespace gpilot
