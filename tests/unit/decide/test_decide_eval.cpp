// gpilot-eval-decide's scoring on hand-made truth and command sequences with known answers.
#include <gtest/gtest.h>

#include "decide_eval.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"

namespace gpilot {
namespace {

constexpr int64_t kFrameUs = 40000;
using G = ground_truth_t;
using M = gesture_cmd_t;

struct Sequence {
  std::vector<TruthFrame> truth;
  std::vector<ScoredCommand> cmds;
  // n frames of a true gesture (expected mode, direction) and of a command
  void add(int n, int gesture, int expected, ScoredCommand cmd, double dx = 0, double dy = 0) {
    for (int i = 0; i < n; ++i) {
      truth.push_back({static_cast<int64_t>(truth.size()) * kFrameUs, gesture, expected, {dx, dy}});
      cmds.push_back(cmd);
    }
  }
};

const ScoredCommand kHoverCmd{M::MODE_HOVER, {0, 0}};
const ScoredCommand kLeft{M::MODE_FINE, {-0.5, 0.02}};
const ScoredCommand kRight{M::MODE_FINE, {0.5, 0.0}};

TEST(DecideScore, ReactionIsFromTheTrueChangeToTheFirstRightCommand) {
  // REST 25 | OUT (left) 50: HOVER for 10 more frames, then FINE | REST 25: FINE for 5 more frames, then HOVER
  Sequence s;
  s.add(25, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(10, G::GESTURE_OUT, M::MODE_FINE, kHoverCmd, -0.5, 0);
  s.add(40, G::GESTURE_OUT, M::MODE_FINE, kLeft, -0.5, 0);
  s.add(5, G::GESTURE_REST, M::MODE_HOVER, kLeft);
  s.add(20, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  const Score sc = score_commands(s.truth, s.cmds, ScoreRules{});
  EXPECT_EQ(sc.frames, 100);
  EXPECT_EQ(sc.changes, 2);
  EXPECT_EQ(sc.missed, 0);
  ASSERT_EQ(sc.reaction_frames.size(), 2u);
  EXPECT_EQ(sc.reaction_frames[0], 10);
  EXPECT_EQ(sc.reaction_frames[1], 5);
  EXPECT_DOUBLE_EQ(sc.reaction_max_s(), 0.4);
  EXPECT_EQ(sc.reaction_max_frames(), 10);
  EXPECT_EQ(sc.old_frames, 15);
  EXPECT_EQ(sc.wrong_frames, 15);
  EXPECT_EQ(sc.false_at_rest, 0);  // FINE held after the arm came down is the old command, not a false one
  EXPECT_EQ(sc.confused, 0);
}

TEST(DecideScore, MotionWhileRestingIsFalseAndCountedInEpisodes) {
  Sequence s;
  s.add(30, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(3, G::GESTURE_REST, M::MODE_HOVER, {M::MODE_CLOSER, {0, 0}});
  s.add(10, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(2, G::GESTURE_REST, M::MODE_HOVER, {M::MODE_DOWN, {0, 0.3}});
  s.add(2, G::GESTURE_REST, M::MODE_HOVER, {M::MODE_UP, {0, -0.3}});
  s.add(1453, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);  // 1500 frames: one minute
  const Score sc = score_commands(s.truth, s.cmds, ScoreRules{});
  EXPECT_EQ(sc.changes, 0);
  EXPECT_EQ(sc.false_at_rest, 3);  // CLOSER, DOWN, UP
  EXPECT_EQ(sc.false_at_rest_frames, 7);
  EXPECT_NEAR(sc.minutes, 1.0, 0.001);
  EXPECT_NEAR(sc.false_per_minute(), 3.0, 0.01);
  EXPECT_EQ(sc.wrong_frames, 7);
}

TEST(DecideScore, AnotherMotionThanTheOneAskedIsConfusedEvenWhileReacting) {
  // CLOSER asked: FURTHER comes first (not the old command: confused), then CLOSER
  Sequence s;
  s.add(20, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(4, G::GESTURE_CLOSER, M::MODE_CLOSER, {M::MODE_FURTHER, {0, 0}});
  s.add(40, G::GESTURE_CLOSER, M::MODE_CLOSER, {M::MODE_CLOSER, {0, 0}});
  const Score sc = score_commands(s.truth, s.cmds, ScoreRules{});
  EXPECT_EQ(sc.confused, 1);
  EXPECT_EQ(sc.confused_frames, 4);
  EXPECT_EQ(sc.reaction_frames.at(0), 4);
  EXPECT_EQ(sc.old_frames, 4);
}

TEST(DecideScore, TheNextGesturesCommandShownByTheTrueHandIsEarlyNotConfused) {
  // OUT, the arm rising: the true hand is in the UP sector 3 frames before the label says UP; UP commanded
  // on the last 2 of them is early. UP commanded while the true hand still points out is confused.
  Sequence s;
  s.add(30, G::GESTURE_OUT, M::MODE_FINE, kLeft, -0.5, 0);
  s.add(1, G::GESTURE_OUT, M::MODE_UP, kLeft, 0, -0.6);
  s.add(2, G::GESTURE_OUT, M::MODE_UP, {M::MODE_UP, {0, -0.6}}, 0, -0.6);
  s.add(30, G::GESTURE_UP, M::MODE_UP, {M::MODE_UP, {0, -0.6}}, 0, -0.6);
  EXPECT_EQ(score_commands(s.truth, s.cmds, ScoreRules{}).confused, 0);
  Sequence t;
  t.add(30, G::GESTURE_OUT, M::MODE_FINE, kLeft, -0.5, 0);
  t.add(2, G::GESTURE_OUT, M::MODE_FINE, {M::MODE_UP, {0, -0.6}}, -0.5, 0);
  t.add(30, G::GESTURE_UP, M::MODE_UP, {M::MODE_UP, {0, -0.6}}, 0, -0.6);
  const Score sc = score_commands(t.truth, t.cmds, ScoreRules{});
  EXPECT_EQ(sc.confused, 1);
  EXPECT_EQ(sc.confused_frames, 2);
}

TEST(DecideScore, ACommandTheTrueHandShowsOnItsWayToRestIsNotFalse) {
  // REST after OUT, the arm lowered slowly: for 15 frames the true hand is out and down (the rules give DOWN);
  // DOWN commanded on 10 of them is not false. DOWN once the true hand shows nothing is.
  Sequence s;
  s.add(40, G::GESTURE_OUT, M::MODE_FINE, kLeft, -0.5, 0);
  s.add(20, G::GESTURE_REST, M::MODE_FINE, kHoverCmd, -0.5, 0);
  s.add(5, G::GESTURE_REST, M::MODE_DOWN, kHoverCmd, -0.2, 0.5);
  s.add(10, G::GESTURE_REST, M::MODE_DOWN, {M::MODE_DOWN, {0, 0.5}}, -0.2, 0.5);
  s.add(40, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  EXPECT_EQ(score_commands(s.truth, s.cmds, ScoreRules{}).false_at_rest, 0);
  Sequence t = s;
  for (size_t i = 75; i < 78; ++i) t.cmds[i] = {M::MODE_DOWN, {0, 0.5}};
  const Score sc = score_commands(t.truth, t.cmds, ScoreRules{});
  EXPECT_EQ(sc.false_at_rest, 1);
  EXPECT_EQ(sc.false_at_rest_frames, 3);
}

TEST(DecideScore, AnArmOnItsWayOutIsOneGestureWithWhereItArrives) {
  // The arm sweeps through directions 60 degrees apart for 0.4 s (10 frames) before it settles: one change,
  // at the label's switch, not a short gesture the command could never catch.
  Sequence s;
  s.add(20, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(10, G::GESTURE_OUT, M::MODE_FINE, kHoverCmd, -0.25, 0.43);
  s.add(40, G::GESTURE_OUT, M::MODE_FINE, kLeft, -0.5, 0);
  const Score sc = score_commands(s.truth, s.cmds, ScoreRules{});
  EXPECT_EQ(sc.changes, 1);
  EXPECT_EQ(sc.missed, 0);
  EXPECT_EQ(sc.reaction_frames.at(0), 10);
}

TEST(DecideScore, PointingTheOtherWayIsANewGestureThatNeedsTheNewDirection) {
  // Left arm out, then the right: FINE all along, but the left direction for 7 frames of the right's gesture
  Sequence s;
  s.add(20, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(40, G::GESTURE_OUT, M::MODE_FINE, kLeft, -0.5, 0);
  s.add(7, G::GESTURE_OUT, M::MODE_FINE, kLeft, 0.5, 0);
  s.add(40, G::GESTURE_OUT, M::MODE_FINE, kRight, 0.5, 0);
  const Score sc = score_commands(s.truth, s.cmds, ScoreRules{});
  EXPECT_EQ(sc.changes, 2);
  ASSERT_EQ(sc.reaction_frames.size(), 2u);
  EXPECT_EQ(sc.reaction_frames[0], 0);
  EXPECT_EQ(sc.reaction_frames[1], 7);
  EXPECT_EQ(sc.confused, 0);  // the right mode, a late direction: slow, not false
}

TEST(DecideScore, ACommandThatNeverComesIsMissedAndAnUnseenGestureIsNotScored) {
  Sequence s;
  s.add(20, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(30, G::GESTURE_UP, M::MODE_HOVER, kHoverCmd);  // out of view: the truth expects nothing
  s.add(20, G::GESTURE_REST, M::MODE_HOVER, kHoverCmd);
  s.add(30, G::GESTURE_DOWN, M::MODE_DOWN, kHoverCmd);  // seen, never commanded
  const Score sc = score_commands(s.truth, s.cmds, ScoreRules{});
  EXPECT_EQ(sc.frames, 70);
  EXPECT_EQ(sc.changes, 2);  // -> REST (reaction 0), -> DOWN (missed)
  EXPECT_EQ(sc.missed, 1);
  EXPECT_EQ(sc.reaction_frames.at(0), 0);
  EXPECT_EQ(sc.old_frames, 30);
}

TEST(DecideScore, PooledScoresAddUp) {
  Score a, b;
  a.reaction_us = {100000, 300000};
  a.reaction_frames = {2, 7};
  a.changes = 2;
  b.reaction_us = {200000};
  b.reaction_frames = {5};
  b.changes = 1;
  b.false_at_rest = 1;
  b.minutes = 0.5;
  a.add(b);
  EXPECT_EQ(a.changes, 3);
  EXPECT_DOUBLE_EQ(a.reaction_median_s(), 0.2);
  EXPECT_EQ(a.reaction_median_frames(), 5);
  EXPECT_DOUBLE_EQ(a.false_per_minute(), 2.0);
}

}  // namespace
}  // namespace gpilot
