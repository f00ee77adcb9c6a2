// StageStats: the numbers a HEALTH message carries, with time passed in by hand.
#include <gtest/gtest.h>

#include "stage_stats.hpp"

namespace gpilot {
namespace {

TEST(StageStats, QuantileNearestRank) {
  std::vector<int64_t> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);
  EXPECT_EQ(quantile(v, 0.5), 50);
  EXPECT_EQ(quantile(v, 0.99), 99);
  EXPECT_EQ(quantile(v, 1.0), 100);
  std::vector<int64_t> none;
  EXPECT_EQ(quantile(none, 0.5), 0);
}

TEST(StageStats, ReportCountsRatesAndPercentiles) {
  // GIVEN a stage that accepted 30 messages and published 15 in the 1 s after its first report
  StageStats s;
  s.set_state(health_t::STATE_OK, "tracking");
  (void)s.report(1'000'000, "gpilot-x", 7);
  for (int i = 0; i < 30; ++i) s.accepted();
  for (int i = 0; i < 15; ++i) s.published();
  for (int i = 1; i <= 100; ++i) s.processing_time(i * 10);  // 10 us .. 1000 us
  s.rejected("CAMERA: image has no pixels (0x3)");
  s.dropped();
  // WHEN the next report is made 1 s later
  const health_t h = s.report(2'000'000, "gpilot-x", 7);
  // THEN it carries the totals, the rates and the percentiles of that period
  EXPECT_EQ(h.seq, 1);
  EXPECT_EQ(h.name, "gpilot-x");
  EXPECT_EQ(h.pid, 7);
  EXPECT_EQ(h.state, health_t::STATE_OK);
  EXPECT_EQ(h.state_detail, "tracking");
  EXPECT_EQ(h.messages_in, 30);
  EXPECT_EQ(h.messages_out, 15);
  EXPECT_EQ(h.rejected, 1);
  EXPECT_EQ(h.dropped, 1);
  EXPECT_EQ(h.last_reject_reason, "CAMERA: image has no pixels (0x3)");
  EXPECT_FLOAT_EQ(h.rate_in_hz, 30.0f);
  EXPECT_FLOAT_EQ(h.rate_out_hz, 15.0f);
  EXPECT_FLOAT_EQ(h.processing_ms_p50, 0.5f);
  EXPECT_FLOAT_EQ(h.processing_ms_p99, 0.99f);
  // AND the period restarts: no new samples, rates fall to 0
  const health_t h2 = s.report(3'000'000, "gpilot-x", 7);
  EXPECT_FLOAT_EQ(h2.rate_in_hz, 0.0f);
  EXPECT_FLOAT_EQ(h2.processing_ms_p50, 0.0f);
  EXPECT_EQ(h2.messages_in, 30);
}

TEST(StageStats, AFailureMakesTheStateErrorUntilTheProcessStops) {
  // GIVEN a stage that says it is tracking
  StageStats s;
  s.set_state(health_t::STATE_OK, "tracking");
  EXPECT_EQ(s.report(1'000'000, "gpilot-x", 7).state, health_t::STATE_OK);
  // WHEN its process fails twice
  EXPECT_EQ(s.failed("CAMERA: bad_alloc"), 1);
  EXPECT_EQ(s.failed("CAMERA: vector::at"), 2);
  // THEN the report says ERROR with the count and the last failure, whatever the stage sets after
  s.set_state(health_t::STATE_OK, "tracking");
  const health_t h = s.report(2'000'000, "gpilot-x", 7);
  EXPECT_EQ(h.state, health_t::STATE_ERROR);
  EXPECT_EQ(h.state_detail, "2 failures of this process, the last: CAMERA: vector::at; tracking");
  EXPECT_EQ(h.rejected, 0);
  // AND stopping is still reported as stopping
  s.set_state(health_t::STATE_STOPPING, "stopping");
  EXPECT_EQ(s.report(3'000'000, "gpilot-x", 7).state, health_t::STATE_STOPPING);
}

}  // namespace
}  // namespace gpilot
