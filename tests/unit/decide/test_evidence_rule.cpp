// EvidenceRule (decide.rule: evidence) on hand-made observation sequences with known reaction times.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "config.hpp"
#include "evidence_rule.hpp"
#include "gesture_decider.hpp"

namespace gpilot {
namespace {

constexpr int kOut = 1, kFront = 2;
constexpr double kBox = 200.0;  // px: moving_ratio 0.03 -> a hand moving more than 6 px a frame supports nothing

// Numbers of their own (not the defaults), so that each test can count its frames. With moving_frames 1 a
// hand is compared with where it was a frame before: its first frame in view is on its way (evidence for nothing).
DecideParams evidence_params() {
  DecideParams p;
  p.rule = "evidence";
  p.evidence_enter = 6;
  p.evidence_leave = 2;
  p.evidence_max = 10;
  p.evidence_decay = 1.0;
  p.moving_ratio = 0.03;
  p.moving_frames = 1;
  p.direction_frames = 8;
  p.front_hold_frames = 1;  // a hand in front counts like any other (the hold has tests of its own)
  return p;
}

TEST(EvidenceRule, ClassifiesOneObservationLikeAlg3SnapsAMean) {
  EXPECT_EQ(EvidenceRule::classify(kOut, {100, -51}, 0.5), EvidenceRule::kUp);
  EXPECT_EQ(EvidenceRule::classify(kOut, {100, -50}, 0.5), EvidenceRule::kFineRight);
  EXPECT_EQ(EvidenceRule::classify(kOut, {-100, 20}, 0.5), EvidenceRule::kFineLeft);
  EXPECT_EQ(EvidenceRule::classify(kOut, {-20, 80}, 0.5), EvidenceRule::kDown);
  EXPECT_EQ(EvidenceRule::classify(kFront, {5, -20}, 0.5), EvidenceRule::kCloser);
  EXPECT_EQ(EvidenceRule::classify(kFront, {5, 20}, 0.5), EvidenceRule::kFurther);
  EXPECT_EQ(EvidenceRule::classify(kFront, {5, 0}, 0.5), EvidenceRule::kNone);
  EXPECT_EQ(EvidenceRule::classify(0, {}, 0.5), EvidenceRule::kNone);
}

TEST(EvidenceRule, SteadyPoseIsEnteredOnItsSeventhFrame) {
  // the first frame has nothing to compare with, then 6 frames of evidence
  EvidenceRule r(evidence_params());
  for (int i = 1; i <= 6; ++i) EXPECT_EQ(r.update(kOut, {-100, 10}, kBox).mode, GestureMode::Hover) << i;
  const Decision d = r.update(kOut, {-100, 10}, kBox);
  EXPECT_EQ(d.mode, GestureMode::Fine);
  EXPECT_DOUBLE_EQ(d.out_mean.x, -100);
  EXPECT_DOUBLE_EQ(d.out_mean.y, 10);
}

TEST(EvidenceRule, HeldPoseIsLetGoEightFramesAfterTheArmComesDown) {
  // GIVEN FINE held long enough to cap its evidence at 10
  EvidenceRule r(evidence_params());
  for (int i = 0; i < 20; ++i) r.update(kOut, {-100, 10}, kBox);
  EXPECT_EQ(r.evidence(EvidenceRule::kFineLeft), 10);
  // WHEN nothing is seen: evidence 9, 8, ... reaches 2 (evidence_leave) on the 8th frame
  for (int i = 1; i <= 7; ++i) EXPECT_EQ(r.update(0, {}, kBox).mode, GestureMode::Fine) << i;
  EXPECT_EQ(r.update(0, {}, kBox).mode, GestureMode::Hover);
}

TEST(EvidenceRule, AStrayFrameInThreeNeverCommands) {
  // +1 for the stray frame, -1 for each of the two others: the evidence never builds up
  EvidenceRule r(evidence_params());
  for (int i = 0; i < 300; ++i)
    EXPECT_EQ(r.update(i % 3 == 0 ? kFront : 0, i % 3 == 0 ? Vec2{0, -30} : Vec2{}, kBox).mode, GestureMode::Hover) << i;
}

TEST(EvidenceRule, AMovingHandIsEvidenceForNothing) {
  // An arm on its way (7 px a frame > 0.03 * 200 px) through the DOWN sector, then held out: DOWN never comes,
  // FINE comes on the 6th still frame.
  EvidenceRule r(evidence_params());
  Vec2 v{-60, 110};
  r.update(kOut, v, kBox);  // the first frame of a hand in view: nothing to compare with, on its way
  for (int i = 0; i < 12; ++i) {
    v = {v.x - 5, v.y - 5};  // 7.1 px a frame
    EXPECT_EQ(r.update(kOut, v, kBox).mode, GestureMode::Hover) << i;
  }
  v = {-150, 10};  // arrives: a jump (moving), then still
  EXPECT_EQ(r.update(kOut, v, kBox).mode, GestureMode::Hover);
  for (int i = 1; i <= 5; ++i) EXPECT_EQ(r.update(kOut, v, kBox).mode, GestureMode::Hover) << i;
  EXPECT_EQ(r.update(kOut, v, kBox).mode, GestureMode::Fine);
  EXPECT_EQ(r.evidence(EvidenceRule::kDown), 0);
}

TEST(EvidenceRule, AnArmLoweredSlowlyDriftsAndIsNotHeld) {
  // 2.5 px a frame down through the DOWN sector: still from one frame to the next (< 0.03 * 200 = 6 px), but
  // the median of the last 3 frames is 7.5 px from that of the 3 before. With moving_frames 3 it never commands
  // DOWN; with 1 it does.
  DecideParams p = evidence_params();
  p.moving_frames = 3;
  EvidenceRule slow(p), jittery(evidence_params());
  bool down_slow = false, down_one = false;
  for (int i = 0; i < 40; ++i) {
    const Vec2 v{-100, 60.0 + 2.5 * i};
    down_slow = down_slow || slow.update(kOut, v, kBox).mode == GestureMode::Down;
    down_one = down_one || jittery.update(kOut, v, kBox).mode == GestureMode::Down;
  }
  EXPECT_FALSE(down_slow);
  EXPECT_TRUE(down_one);
  // and a pose held with a pixel of jitter is commanded once both 3-frame medians exist (6th frame) and 6 frames
  // of evidence later (11th)
  EvidenceRule held(p);
  GestureMode m = GestureMode::Hover;
  for (int i = 0; i < 10; ++i) EXPECT_EQ(held.update(kOut, {-100.0 + (i % 2), 120}, kBox).mode, GestureMode::Hover) << i;
  for (int i = 10; i < 11; ++i) m = held.update(kOut, {-100.0 + (i % 2), 120}, kBox).mode;
  EXPECT_EQ(m, GestureMode::Down);
}

TEST(EvidenceRule, AHandFoundOffItsPlaceNowAndThenMovesNoMedian) {
  // Held out, found 50 px off its place every 4th frame (a noisy image): with 3-frame medians the pose is
  // commanded and stays commanded; with 1 frame each jump is motion and the evidence keeps falling back.
  DecideParams p = evidence_params();
  p.moving_frames = 3;
  EvidenceRule medians(p), single(evidence_params());
  int held_medians = 0, held_single = 0;
  for (int i = 0; i < 100; ++i) {
    const Vec2 v = i % 4 == 3 ? Vec2{-100, 10} : Vec2{-150, 10};
    held_medians += medians.update(kOut, v, kBox).mode == GestureMode::Fine;
    held_single += single.update(kOut, v, kBox).mode == GestureMode::Fine;
  }
  EXPECT_EQ(held_medians, 100 - 10);  // from the 11th frame on (6 frames to have both medians, 6 of evidence)
  EXPECT_EQ(held_single, 0);
}

TEST(EvidenceRule, PointingTheOtherWaySwitchesWithoutAveragingBothArms) {
  EvidenceRule r(evidence_params());
  for (int i = 0; i < 20; ++i) r.update(kOut, {-150, 5}, kBox);
  // The right arm out: its first frame is a jump across the image (moving: evidence for nothing), then its
  // evidence is 1..6 while the left's falls 8..3; the 7th frame switches (6 >= enter and 6 > 3).
  for (int i = 1; i <= 6; ++i) {
    const Decision d = r.update(kOut, {148, 4}, kBox);
    EXPECT_EQ(d.mode, GestureMode::Fine);
    EXPECT_DOUBLE_EQ(d.out_mean.x, -150) << i;  // still the left arm's direction, never a mix of both
  }
  const Decision d = r.update(kOut, {148, 4}, kBox);
  EXPECT_EQ(d.mode, GestureMode::Fine);
  EXPECT_DOUBLE_EQ(d.out_mean.x, 148);
}

TEST(EvidenceRule, UpAndDownSnapXAndFrontGivesZ) {
  EvidenceRule r(evidence_params());
  Decision d;
  for (int i = 0; i < 7; ++i) d = r.update(kOut, {30, -90}, kBox);
  EXPECT_EQ(d.mode, GestureMode::Up);
  EXPECT_EQ(d.out_mean.x, 0.0);
  EXPECT_DOUBLE_EQ(d.out_mean.y, -90);
  EvidenceRule f(evidence_params());
  for (int i = 0; i < 7; ++i) d = f.update(kFront, {2, 25}, kBox);
  EXPECT_EQ(d.mode, GestureMode::Further);
  EXPECT_EQ(d.z, -1.0);
}

TEST(EvidenceRule, ThresholdsComeFromParams) {
  DecideParams p = evidence_params();
  p.evidence_enter = 3;
  EvidenceRule r(p);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.update(kFront, {0, -30}, kBox).mode, GestureMode::Hover) << i;
  EXPECT_EQ(r.update(kFront, {0, -30}, kBox).mode, GestureMode::Closer);
}

// The first frame a decider fed o (a new observation every 40 ms) gives mode, 1-based; 0 if none of n does.
int first_frame_of(const DecideParams& p, HandObservation o, GestureMode mode, int n) {
  GestureDecider d(p);
  for (int i = 0; i < n; ++i) {
    o.utime = 1'000'000 + i * 40'000;
    o.seq = i;
    if (d.update(o).mode == mode) return i + 1;
  }
  return 0;
}

TEST(GestureDeciderEvidence, TheDefaultIsTheEvidenceRule) {
  const DecideParams p;
  EXPECT_EQ(p.rule, "evidence");
  HandObservation o;
  o.user_box_width = kBox;
  o.track_id = 1;
  // A steady arm out is commanded on its 6th frame (0.2 s at 25 fps: two 2-frame medians to tell it still, then
  // 3 frames of evidence), the paper's Alg. 3 on its 31st.
  o.kind = HandObservation::Kind::Out;
  o.vector = {-100, 0};
  EXPECT_EQ(first_frame_of(p, o, GestureMode::Fine, 40), 6);
  // A steady hand in front on its 17th (0.64 s: 15 frames held, then 3 of evidence).
  o.kind = HandObservation::Kind::Front;
  o.vector = {0, -30};
  EXPECT_EQ(first_frame_of(p, o, GestureMode::Closer, 40), 17);
}

TEST(EvidenceRule, AHandInFrontAtTheBodyCentresHeightIsNeitherHigherNorLower) {
  // classify: within the dead band (px) of the body centre's height, no class; beyond it, the paper's sign
  EXPECT_EQ(EvidenceRule::classify(kFront, {5, -9}, 0.5, 10.0), EvidenceRule::kNone);
  EXPECT_EQ(EvidenceRule::classify(kFront, {5, 9}, 0.5, 10.0), EvidenceRule::kNone);
  EXPECT_EQ(EvidenceRule::classify(kFront, {5, -11}, 0.5, 10.0), EvidenceRule::kCloser);
  EXPECT_EQ(EvidenceRule::classify(kFront, {5, 11}, 0.5, 10.0), EvidenceRule::kFurther);
  // the defaults (0.05 box widths): a hand held 0.03 box widths below the body centre is no command, 0.1 is
  const DecideParams p;
  EvidenceRule r(p);
  for (int i = 0; i < 40; ++i) EXPECT_EQ(r.update(kFront, {20, 0.03 * kBox}, kBox).mode, GestureMode::Hover) << i;
  GestureMode m = GestureMode::Hover;
  for (int i = 0; i < 40 && m == GestureMode::Hover; ++i) m = r.update(kFront, {20, 0.1 * kBox}, kBox).mode;
  EXPECT_EQ(m, GestureMode::Further);
}

TEST(EvidenceRule, HandsMovedAboutInFrontAsInTalkingAreNoCommand) {
  // GIVEN the defaults and a hand in front, below the body centre (FURTHER's side), that moves to a new place
  // every 14 frames (0.56 s), 0.2 box widths away, in 3 frames, and rests there
  const DecideParams p;
  EvidenceRule r(p);
  const Vec2 places[] = {{10, 40}, {50, 50}, {20, 80}, {-20, 45}, {30, 60}};
  Vec2 at = places[0];
  int commanded = 0;
  for (int k = 0; k < 20; ++k) {
    const Vec2 to = places[k % 5];
    for (int i = 1; i <= 14; ++i) {
      const double f = std::min(1.0, i / 3.0);
      commanded += r.update(kFront, {at.x + f * (to.x - at.x), at.y + f * (to.y - at.y)}, kBox).mode != GestureMode::Hover;
    }
    at = to;
  }
  // THEN never commanded
  EXPECT_EQ(commanded, 0);
  // AND the same hand that stays at its last place is FURTHER within 17 frames
  GestureMode m = GestureMode::Hover;
  for (int i = 0; i < 17 && m == GestureMode::Hover; ++i) m = r.update(kFront, at, kBox).mode;
  EXPECT_EQ(m, GestureMode::Further);
}

TEST(EvidenceRule, AHeldHandInFrontThatMovesOnIsLetGo) {
  // GIVEN CLOSER held long enough to cap its evidence (defaults: leave at 2 of 10)
  const DecideParams p;
  EvidenceRule r(p);
  for (int i = 0; i < 30; ++i) r.update(kFront, {0, -30}, kBox);
  ASSERT_EQ(r.current(), EvidenceRule::kCloser);
  // WHEN the hand moves on, still above the body centre (CLOSER's side), 8 px a frame
  int frames = 0;
  for (; frames < 20 && r.current() == EvidenceRule::kCloser; ++frames) r.update(kFront, {8.0 * frames, -30}, kBox);
  // THEN let go once the motion shows (two 2-frame medians apart) and 8 frames of evidence are lost
  EXPECT_LE(frames, 11);
  EXPECT_GE(frames, 8);
  // while an arm out that sweeps within FINE is still FINE (fine piloting)
  EvidenceRule out(p);
  for (int i = 0; i < 30; ++i) out.update(kOut, {-100, 0}, kBox);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(out.update(kOut, {-100.0 - 8 * i, 0}, kBox).mode, GestureMode::Fine) << i;
}

TEST(GestureDeciderEvidence, RuleIsChosenByConfigAndResetsWithTheBuffers) {
  GestureDecider d(evidence_params());
  HandObservation o;
  o.kind = HandObservation::Kind::Out;
  o.vector = {-100, 0};
  o.user_box_width = kBox;
  o.track_id = 1;
  GestureCommand c;
  for (int i = 0; i < 7; ++i) {
    o.utime = 1'000'000 + i * 40'000;
    o.seq = i;
    c = d.update(o);
  }
  EXPECT_EQ(c.mode, GestureMode::Fine);  // the 7th frame: Alg. 3 would wait for the 31st
  EXPECT_DOUBLE_EQ(c.direction[0], -0.5);
  EXPECT_EQ(c.n_out, 7);                 // the buffers' counts still go out
  o.utime += 600'000;                    // a gap: everything starts again
  EXPECT_EQ(d.update(o).mode, GestureMode::Hover);
  EXPECT_EQ(d.last_reset(), GestureDecider::Reset::Gap);
}

TEST(GestureDeciderEvidence, UnknownRuleIsAConfigError) {
  Config c;
  c.set("decide.rule=fastest");
  EXPECT_THROW(c.section<DecideParams>("decide"), ConfigError);
  Config ok;
  ok.set("decide.rule=paper");
  EXPECT_EQ(ok.section<DecideParams>("decide").rule, "paper");
}

}  // namespace
}  // namespace gpilot
