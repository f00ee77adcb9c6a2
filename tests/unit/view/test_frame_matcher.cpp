// Frames and their messages are put together by seq, released in order, held at most --hold frames.
#include <gtest/gtest.h>

#include "frame_matcher.hpp"
#include "synthetic_run.hpp"

namespace gpilot {
namespace {

class FrameMatcherTest : public ::testing::Test {
 protected:
  void frame(int64_t s) { m.add_frame(test::camera_of(run, s)); }
  void all_messages(int64_t s) {
    m.add(test::track_of(run, s));
    m.add(test::hand_of(run, s));
    m.add(test::cmd_of(run, s));
  }
  void SetUp() override { run.size = cv::Size(32, 24); }
  test::SyntheticRun run;
  FrameMatcher m{3};
};

TEST_F(FrameMatcherTest, MessagesArrivingFramesLaterLandOnTheirOwnFrame) {
  // GIVEN frames 0..3 and then the messages of frame 0
  frame(0);
  frame(1);
  frame(2);
  all_messages(0);
  frame(3);
  // WHEN the matcher is asked; THEN frame 0 comes out complete with frame 0's messages
  auto ready = m.take_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].image.seq, 0);
  EXPECT_TRUE(ready[0].complete);
  ASSERT_TRUE(ready[0].msgs.track && ready[0].msgs.hand && ready[0].msgs.cmd);
  EXPECT_EQ(ready[0].msgs.track->seq, 0);
  EXPECT_EQ(ready[0].msgs.cmd->seq, 0);
  EXPECT_FALSE(ready[0].msgs.truth.has_value());
}

TEST_F(FrameMatcherTest, ACompleteFrameWaitsForANewerFrame) {
  // GIVEN the channel set learnt over the first frames
  for (int s = 0; s < 4; ++s) {
    frame(s);
    all_messages(s);
  }
  EXPECT_EQ(m.take_ready().size(), 3u);
  // WHEN frame 4 is complete; THEN it still waits for frame 5 (a slower channel could yet show up)
  frame(4);
  all_messages(4);
  auto ready = m.take_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].image.seq, 3);
  frame(5);
  ready = m.take_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].image.seq, 4);
}

TEST_F(FrameMatcherTest, TheFirstFramesWaitForChannelsNotSeenYet) {
  // GIVEN frame 0 and 1 with USER_TRACK only, GESTURE_CMD of frame 0 arriving after frame 2
  frame(0);
  m.add(test::track_of(run, 0));
  frame(1);
  m.add(test::track_of(run, 1));
  frame(2);
  EXPECT_TRUE(m.take_ready().empty());
  m.add(test::cmd_of(run, 0));
  // WHEN frame 3 comes; THEN frame 0 is drawn with its command
  frame(3);
  auto ready = m.take_ready();
  ASSERT_GE(ready.size(), 1u);
  EXPECT_TRUE(ready[0].msgs.cmd.has_value());
}

TEST_F(FrameMatcherTest, AFrameMissingAMessageIsHeldHoldFramesThenDrawnAnyway) {
  // GIVEN HAND_OBS has been seen (frame 1) but never comes for frame 0
  frame(0);
  m.add(test::track_of(run, 0));
  m.add(test::cmd_of(run, 0));
  frame(1);
  all_messages(1);
  frame(2);
  EXPECT_TRUE(m.take_ready().empty());  // frame 0 waits (2 newer frames); frame 1 is behind it
  // WHEN a third newer frame comes; THEN frame 0 is released incomplete, frame 1 complete after it
  frame(3);
  auto ready = m.take_ready();
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_EQ(ready[0].image.seq, 0);
  EXPECT_FALSE(ready[0].complete);
  EXPECT_FALSE(ready[0].msgs.hand.has_value());
  EXPECT_EQ(ready[1].image.seq, 1);
  EXPECT_TRUE(ready[1].complete);
  EXPECT_EQ(m.incomplete_frames(), 1);
}

TEST_F(FrameMatcherTest, MessagesBeforeTheirFrameAreKept) {
  m.add(test::track_of(run, 0));
  frame(0);
  frame(1);
  frame(2);
  frame(3);
  auto ready = m.take_ready();
  ASSERT_EQ(ready.size(), 1u);
  ASSERT_TRUE(ready[0].msgs.track.has_value());
  EXPECT_EQ(ready[0].msgs.track->seq, 0);
}

TEST_F(FrameMatcherTest, LateMessagesAreCountedAndDropped) {
  frame(0);
  m.add(test::track_of(run, 0));
  for (int s = 1; s <= 3; ++s) frame(s);
  ASSERT_EQ(m.take_ready().size(), 1u);
  m.add(test::cmd_of(run, 0));
  EXPECT_EQ(m.late_messages(), 1);
  EXPECT_EQ(m.pending_frames(), 3u);
}

TEST_F(FrameMatcherTest, FlushReleasesEverythingInOrder) {
  for (int s = 0; s < 3; ++s) frame(s);
  m.add(test::track_of(run, 1));
  auto out = m.flush();
  ASSERT_EQ(out.size(), 3u);
  for (int s = 0; s < 3; ++s) EXPECT_EQ(out[s].image.seq, s);
  EXPECT_TRUE(out[1].msgs.track.has_value());
  EXPECT_EQ(m.pending_frames(), 0u);
}

TEST_F(FrameMatcherTest, ASourceRestartReleasesTheOldFramesFirst) {
  frame(5);
  frame(6);
  m.add(test::track_of(run, 5));
  frame(0);  // the source starts again
  m.add(test::track_of(run, 0));
  for (int s = 1; s <= 3; ++s) frame(s);
  auto ready = m.take_ready();
  ASSERT_GE(ready.size(), 3u);
  EXPECT_EQ(ready[0].image.seq, 5);
  EXPECT_EQ(ready[1].image.seq, 6);
  EXPECT_EQ(ready[2].image.seq, 0);
  ASSERT_TRUE(ready[2].msgs.track.has_value());
  EXPECT_EQ(ready[2].msgs.track->seq, 0);
}

TEST_F(FrameMatcherTest, MessagesWhoseFrameNeverCameAreOrphans) {
  frame(0);
  m.add(test::track_of(run, 1));  // frame 1 is lost
  frame(2);
  frame(3);
  frame(4);
  frame(5);  // frames 0 and 2 have no USER_TRACK: each is released once 3 newer frames came
  auto ready = m.take_ready();
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_EQ(ready[0].image.seq, 0);
  EXPECT_EQ(ready[1].image.seq, 2);
  EXPECT_EQ(m.orphan_messages(), 1);
}

}  // namespace
}  // namespace gpilot
