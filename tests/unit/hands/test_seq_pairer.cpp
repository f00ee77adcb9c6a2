// CAMERA/USER_TRACK pairing by seq: either order, never across seqs, unmatched items dropped and counted.
#include <gtest/gtest.h>

#include <string>

#include "hands/seq_pairer.hpp"

using gpilot::SeqPairer;

TEST(SeqPairer, PairsInEitherOrder) {
  SeqPairer<std::string, int> p(5);
  EXPECT_FALSE(p.add_frame(1, "f1"));
  auto a = p.add_track(1, 10);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->first, "f1");
  EXPECT_EQ(a->second, 10);
  EXPECT_FALSE(p.add_track(2, 20));
  auto b = p.add_frame(2, "f2");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->first, "f2");
  EXPECT_EQ(b->second, 20);
  EXPECT_EQ(p.waiting(), 0u);
  EXPECT_EQ(p.dropped_frames() + p.dropped_tracks(), 0);
}

TEST(SeqPairer, NeverPairsDifferentSeqsAndDropsTheUnmatched) {
  SeqPairer<std::string, int> p(3);
  EXPECT_FALSE(p.add_frame(1, "f1"));
  EXPECT_FALSE(p.add_track(2, 20));  // a track for a frame that never came
  EXPECT_FALSE(p.add_frame(3, "f3"));
  EXPECT_EQ(p.dropped_frames(), 0);
  EXPECT_FALSE(p.add_frame(4, "f4"));  // newest 4: seq 1 is 3 behind, dropped
  EXPECT_EQ(p.dropped_frames(), 1);
  EXPECT_FALSE(p.add_frame(5, "f5"));  // track 2 dropped
  EXPECT_EQ(p.dropped_tracks(), 1);
  auto m = p.add_track(4, 40);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->first, "f4");
  EXPECT_FALSE(p.add_track(1, 10));  // frame 1 is gone: a late track is dropped, not paired with another frame
  EXPECT_EQ(p.dropped_tracks(), 2);
}

TEST(SeqPairer, ADuplicateSeqReplacesAndCounts) {
  SeqPairer<std::string, int> p(5);
  p.add_frame(7, "old");
  p.add_frame(7, "new");
  EXPECT_EQ(p.dropped_frames(), 1);
  EXPECT_EQ(p.add_track(7, 70)->first, "new");
}

TEST(SeqPairer, ARestartedSourceStartsAfresh) {
  SeqPairer<std::string, int> p(2);
  p.add_frame(1000, "late");
  EXPECT_FALSE(p.add_frame(0, "f0"));  // far below: restart, the waiting frame is dropped
  EXPECT_EQ(p.dropped_frames(), 1);
  EXPECT_EQ(p.add_track(0, 1)->first, "f0");
}
