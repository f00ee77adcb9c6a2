// Known answers of the frame bookkeeping behind exact replays: SeqGaps (the frames a stage with a bounded
// CAMERA queue never saw) and ReplayPacing (a replay gives a stage only the frames the live stage processed).
#include <gtest/gtest.h>

#include "replay_pacing.hpp"
#include "seq_gaps.hpp"

namespace gpilot {
namespace {

TEST(SeqGaps, CountsTheSeqsSkippedBetweenFramesNotRestarts) {
  SeqGaps g(100);
  EXPECT_EQ(g.skipped_before(10), 0);   // the first frame
  EXPECT_EQ(g.skipped_before(11), 0);
  EXPECT_EQ(g.skipped_before(15), 3);   // 12, 13, 14
  EXPECT_EQ(g.skipped_before(15), 0);   // a repeat
  EXPECT_EQ(g.skipped_before(2), 0);    // a restart of the capture
  EXPECT_EQ(g.skipped_before(103), 100);
  EXPECT_EQ(g.skipped_before(300), 0);  // beyond max_gap: a restart too
}

TEST(ReplayPacing, GivesOnlyTheFramesWithARecordedOutput) {
  ReplayPacing p;
  p.add_rule("CAMERA", "USER_TRACK");
  EXPECT_EQ(p.output_channels(), std::set<std::string>{"USER_TRACK"});
  // A log without USER_TRACK at all (a camera log): every frame.
  EXPECT_TRUE(p.give("CAMERA", 7));
  p.recorded("USER_TRACK", 1);
  p.recorded("USER_TRACK", 3);
  EXPECT_TRUE(p.give("CAMERA", 1));
  EXPECT_FALSE(p.give("CAMERA", 2));  // skipped live
  EXPECT_TRUE(p.give("CAMERA", 3));
  EXPECT_TRUE(p.give("TRACKER_INIT", 2));  // not paced
  EXPECT_EQ(p.held_back(), 1);
  // A chain: a frame goes to the bus when any stage processed it live.
  p.add_rule("CAMERA", "HAND_OBS");
  p.recorded("HAND_OBS", 2);
  EXPECT_TRUE(p.give("CAMERA", 2));
  EXPECT_FALSE(p.give("CAMERA", 4));
}

}  // namespace
}  // namespace gpilot
