// ReplayTicks (tools/replay/replay_ticks.hpp): a logged input of a keyed channel reaches the replayed stage
// just before the first recorded tick that names it, never before a tick that does not; the tick's instant is
// the recorded output's own utime.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "replay_ticks.hpp"

namespace gpilot {
namespace {

using Bytes = ReplayTicks::Bytes;

// Test messages: one byte, the key. A recorded output: {utime, named key}.
ReplayTicks ticks() {
  return ReplayTicks(
      "OUT",
      [](const Bytes& b, int64_t* utime, std::map<std::string, int64_t>* keys) {
        if (b.size() != 2) return false;
        *utime = b[0];
        (*keys)["IN"] = b[1];
        return true;
      },
      {{"IN", [](const Bytes& b) { return static_cast<int64_t>(b[0]); }}}, {{"IN", 0}});
}

TEST(ReplayTicks, AnInputReachesTheStageBeforeTheFirstTickThatNamesIt) {
  ReplayTicks t = ticks();
  std::vector<std::pair<int64_t, int>> delivered;  // (log time, key)
  const auto deliver = [&](const std::string& ch, int64_t ts, const Bytes& b) {
    EXPECT_EQ(ch, "IN");
    delivered.emplace_back(ts, b[0]);
  };
  // GIVEN inputs 1 and 2 logged before a tick that had only 1 (2 was sent just before it, not yet dispatched)
  EXPECT_TRUE(t.keyed("IN"));
  EXPECT_FALSE(t.keyed("OTHER"));
  t.hold("IN", 100, Bytes{1});
  t.hold("IN", 101, Bytes{2});
  // WHEN that tick is replayed THEN only 1 is delivered, at its own log time, and the tick is at its utime
  EXPECT_EQ(t.tick(Bytes{50, 1}, deliver), 50);
  ASSERT_EQ(delivered.size(), 1u);
  EXPECT_EQ(delivered[0], std::make_pair(int64_t{100}, 1));
  // WHEN the next tick names 1 again (nothing newer yet) THEN nothing is delivered, 2 stays held
  EXPECT_EQ(t.tick(Bytes{70, 1}, deliver), 70);
  EXPECT_EQ(delivered.size(), 1u);
  EXPECT_EQ(t.held(), 1u);
  // WHEN 3 is logged and a tick names 3 THEN 2 and 3 are delivered in log order
  t.hold("IN", 102, Bytes{3});
  EXPECT_EQ(t.tick(Bytes{90, 3}, deliver), 90);
  ASSERT_EQ(delivered.size(), 3u);
  EXPECT_EQ(delivered[1].second, 2);
  EXPECT_EQ(delivered[2].second, 3);
  EXPECT_EQ(t.held(), 0u);
  EXPECT_EQ(t.not_logged(), 0);
  // WHEN a tick names 5, which the log lacks (4 is logged) THEN 4 stays held and the tick is counted
  t.hold("IN", 103, Bytes{4});
  EXPECT_EQ(t.tick(Bytes{110, 5}, deliver), 110);
  EXPECT_EQ(delivered.size(), 3u);
  EXPECT_EQ(t.not_logged(), 1);
  // AND a tick without any input of the channel (key 0) is not
  EXPECT_EQ(t.tick(Bytes{120, 0}, deliver), 120);
  EXPECT_EQ(t.not_logged(), 1);
  // AND an output that does not read is no tick
  EXPECT_EQ(t.tick(Bytes{1, 2, 3}, deliver), -1);
}

}  // namespace
}  // namespace gpilot
