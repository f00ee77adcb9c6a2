// Counts the frames a stage never saw. A stage that reads CAMERA through a bounded queue (BusNode::subscribe's
// queue_capacity) skips the oldest frames when it falls behind, and LCM drops them before the stage sees them:
// the gaps in the frames' seq are the only trace. Each skipped frame goes to HEALTH.dropped (BusNode::drop).
#pragma once

#include <cstdint>

namespace gpilot {

class SeqGaps {
 public:
  // A jump by more than max_gap seqs is a restart of the stream (a new capture process), not a loss.
  explicit SeqGaps(int64_t max_gap = 250) : max_gap_(max_gap) {}

  // Frames skipped just before seq: 0 for the first frame, a repeat, a restart (seq not after the last one)
  // or a jump beyond max_gap.
  int64_t skipped_before(int64_t seq) {
    const int64_t gap = have_ && seq > last_ + 1 && seq - last_ - 1 <= max_gap_ ? seq - last_ - 1 : 0;
    last_ = seq;
    have_ = true;
    return gap;
  }

 private:
  int64_t max_gap_;
  int64_t last_ = 0;
  bool have_ = false;
};

}  // namespace gpilot
