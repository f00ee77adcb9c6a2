// Alg. 3 on hand-written buffers: each branch, the "> 30" boundaries, the lambda4 snap, non-zero means.
#include <gtest/gtest.h>

#include "decision_tree.hpp"

namespace gpilot {
namespace {

struct Buffers {
  StateBuffer out{60};
  StateBuffer front{60};
  // n entries of v in S_out (zeros in S_front), the rest of the 60 zero in both.
  void fill_out(int n, Vec2 v) {
    for (int i = 0; i < 60; ++i) {
      out.push(i < n ? v : Vec2{});
      front.push({});
    }
  }
  void fill_front(int n, Vec2 v) {
    for (int i = 0; i < 60; ++i) {
      out.push({});
      front.push(i < n ? v : Vec2{});
    }
  }
};

Decision decide(const Buffers& b) { return DecisionTree(DecideParams{}).decide(b.out, b.front); }

TEST(StateBuffer, KeepsOnlyTheLastCapacityEntries) {
  StateBuffer b(3);
  b.push({1, 1});
  b.push({2, 2});
  b.push({3, 3});
  b.push({0, 0});  // evicts (1, 1)
  EXPECT_EQ(b.size(), 3);
  EXPECT_EQ(b.count_nonzero(), 2);
  EXPECT_DOUBLE_EQ(b.mean_nonzero().x, 2.5);
  b.clear();
  EXPECT_EQ(b.size(), 0);
  EXPECT_EQ(b.count_nonzero(), 0);
}

TEST(DecisionTree, EmptyBuffersHover) {
  Buffers b;
  const Decision d = decide(b);
  EXPECT_EQ(d.mode, GestureMode::Hover);
  EXPECT_EQ(d.n_out, 0);
}

TEST(DecisionTree, ThirtyOutEntriesIsNotEnoughThirtyOneIs) {
  Buffers b30, b31;
  b30.fill_out(30, {-100, 10});
  b31.fill_out(31, {-100, 10});
  EXPECT_EQ(decide(b30).mode, GestureMode::Hover);
  EXPECT_EQ(decide(b30).n_out, 30);
  const Decision d = decide(b31);
  EXPECT_EQ(d.mode, GestureMode::Fine);
  EXPECT_EQ(d.n_out, 31);
  EXPECT_DOUBLE_EQ(d.out_mean.x, -100);
  EXPECT_DOUBLE_EQ(d.out_mean.y, 10);
  EXPECT_EQ(d.z, 0.0);
}

TEST(DecisionTree, MeanIsOverNonZeroEntriesOnly) {
  // GIVEN 20 entries (-90, 0), 20 entries (-120, 30) and 20 zeros: the mean of the 40 non-zero ones
  Buffers b;
  for (int i = 0; i < 20; ++i) b.out.push({-90, 0});
  for (int i = 0; i < 20; ++i) b.out.push({-120, 30});
  for (int i = 0; i < 20; ++i) b.out.push({});
  const Decision d = decide(b);
  EXPECT_EQ(d.mode, GestureMode::Fine);
  EXPECT_DOUBLE_EQ(d.out_mean.x, -105);  // not -70 (which a mean over all 60 would give)
  EXPECT_DOUBLE_EQ(d.out_mean.y, 15);
}

TEST(DecisionTree, Lambda4SnapsSteepVectorsToVertical) {
  // |y| > |0.5 x| -> x := 0. (100, -51): 51 > 50 -> UP; (100, -50): 50 > 50 is false -> FINE.
  Buffers up, fine, down;
  up.fill_out(40, {100, -51});
  fine.fill_out(40, {100, -50});
  down.fill_out(40, {-20, 80});
  const Decision du = decide(up);
  EXPECT_EQ(du.mode, GestureMode::Up);
  EXPECT_EQ(du.out_mean.x, 0.0);
  EXPECT_DOUBLE_EQ(du.out_mean.y, -51);
  const Decision df = decide(fine);
  EXPECT_EQ(df.mode, GestureMode::Fine);
  EXPECT_DOUBLE_EQ(df.out_mean.x, 100);
  const Decision dd = decide(down);
  EXPECT_EQ(dd.mode, GestureMode::Down);
  EXPECT_EQ(dd.out_mean.x, 0.0);
  EXPECT_DOUBLE_EQ(dd.out_mean.y, 80);
}

TEST(DecisionTree, FrontHigherComesCloserLowerGoesFurtherAtTheBoundary) {
  Buffers h30, h31, l30, l31;
  h30.fill_front(30, {5, -20});
  h31.fill_front(31, {5, -20});
  l30.fill_front(30, {5, 20});
  l31.fill_front(31, {5, 20});
  EXPECT_EQ(decide(h30).mode, GestureMode::Hover);
  EXPECT_EQ(decide(h31).mode, GestureMode::Closer);
  EXPECT_EQ(decide(h31).z, 1.0);
  EXPECT_EQ(decide(h31).n_front_higher, 31);
  EXPECT_EQ(decide(l30).mode, GestureMode::Hover);
  EXPECT_EQ(decide(l31).mode, GestureMode::Further);
  EXPECT_EQ(decide(l31).z, -1.0);
  EXPECT_EQ(decide(l31).n_front_lower, 31);
}

TEST(DecisionTree, OutHasPriorityOverFront) {
  // GIVEN both buffers past their thresholds: S_out 31 of 60 non-zero, S_front all 60 above the body centre
  Buffers b;
  for (int i = 0; i < 60; ++i) {
    b.out.push(i < 31 ? Vec2{-50, 0} : Vec2{});
    b.front.push({0, -10});
  }
  const Decision d = decide(b);
  ASSERT_GT(d.n_out, DecideParams{}.out_threshold);
  ASSERT_GT(d.n_front_higher, DecideParams{}.front_threshold);
  // and S_front alone would come closer
  Buffers front_only;
  front_only.fill_front(60, {0, -10});
  ASSERT_EQ(decide(front_only).mode, GestureMode::Closer);
  // THEN Alg. 3 tests S_out first: FINE
  EXPECT_EQ(d.mode, GestureMode::Fine);
}

TEST(DecisionTree, MixedFrontBelowThresholdOnBothSidesHovers) {
  Buffers b;
  for (int i = 0; i < 30; ++i) b.front.push({0, -10});
  for (int i = 0; i < 30; ++i) b.front.push({0, 10});
  const Decision d = decide(b);
  EXPECT_EQ(d.mode, GestureMode::Hover);
  EXPECT_EQ(d.n_front_higher, 30);
  EXPECT_EQ(d.n_front_lower, 30);
}

TEST(DecisionTree, ThresholdsAndLambda4ComeFromParams) {
  DecideParams p;
  p.out_threshold = 5;
  p.lambda4 = 2.0;  // |y| > |2x| needed to snap
  StateBuffer out(60), front(60);
  for (int i = 0; i < 6; ++i) out.push({100, -150});
  const Decision d = DecisionTree(p).decide(out, front);
  EXPECT_EQ(d.mode, GestureMode::Fine);  // 150 > 200 is false: no snap with lambda4 = 2
}

}  // namespace
}  // namespace gpilot
