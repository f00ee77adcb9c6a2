// PairHold (tools/replay/pair_hold.hpp): which order a pairing stage is given its two inputs. Known answers
// of the class; and, on the committed hands log, a replay that does not depend on the order the log heard
// CAMERA and USER_TRACK in: GIVEN the log rewritten with every USER_TRACK 20 frames late (a tracker behind
// under load, as the live hands stage may have had it, whose pairer waits 15 seqs) WHEN hands is replayed
// THEN every HAND_OBS is given again, unchanged.
#include <gtest/gtest.h>

#include <cstdio>
#include <deque>
#include <filesystem>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "pair_hold.hpp"
#include "run_command.hpp"

namespace gpilot {
namespace {

std::vector<uint8_t> bytes(uint8_t b) { return {b}; }

TEST(PairHold, AHeldMessageIsGivenWithItsPartnerAndOneThatNeverMeetsItGoes) {
  PairHold h("CAMERA", "USER_TRACK");
  EXPECT_TRUE(h.holds("CAMERA"));
  EXPECT_TRUE(h.is_partner("USER_TRACK"));
  EXPECT_FALSE(h.holds("USER_TRACK"));
  h.hold(1, 100, bytes(1));
  h.hold(2, 140, bytes(2));
  h.hold(3, 180, bytes(3));
  EXPECT_EQ(h.waiting(), 3u);
  const auto one = h.release(1);
  ASSERT_TRUE(one);
  EXPECT_EQ(one->timestamp, 100);
  EXPECT_EQ(one->bytes, bytes(1));
  // Frame 2's track never comes (the live tracker skipped it): the track of 3 releases 3 and drops 2.
  const auto three = h.release(3);
  ASSERT_TRUE(three);
  EXPECT_EQ(three->bytes, bytes(3));
  EXPECT_EQ(h.waiting(), 0u);
  EXPECT_EQ(h.never_paired(), 1);
  // A track whose frame is not held (the live hands stage skipped that frame): nothing.
  EXPECT_FALSE(h.release(4));
  // A restarted capture's low seqs are not dropped by the old stream's later tracks.
  h.hold(2, 500, bytes(9));
  EXPECT_FALSE(h.release(5000));
  EXPECT_EQ(h.waiting(), 1u);
  EXPECT_TRUE(h.release(2));
}

TEST(PairHold, HandsReplaysTheSamePairsWhenEveryTrackComesLate) {
  const std::string log = std::string(GPILOT_SOURCE_DIR) + "/tests/replay/logs/hands.lcmlog";
  const std::string late = std::filesystem::temp_directory_path() / ("gpilot-late-tracks-" + std::to_string(getpid()) + ".lcmlog");
  {
    lcm::LogFile in(log, "r"), out(late, "w");
    ASSERT_TRUE(in.good() && out.good());
    std::deque<lcm::LogEvent> tracks;  // copies whose data lives in `kept`
    std::deque<std::vector<uint8_t>> kept;
    int64_t eventnum = 0, moved = 0;
    const auto write = [&](lcm::LogEvent e) {
      e.eventnum = eventnum++;
      out.writeEvent(&e);
    };
    for (const lcm::LogEvent* ev = in.readNextEvent(); ev; ev = in.readNextEvent()) {
      if (ev->channel == "USER_TRACK") {
        const auto* p = static_cast<const uint8_t*>(ev->data);
        kept.emplace_back(p, p + ev->datalen);
        tracks.push_back(*ev);
        tracks.back().data = kept.back().data();
        continue;
      }
      write(*ev);
      if (ev->channel == "CAMERA" && tracks.size() > 20) {  // a track goes out 20 frames after its own
        write(tracks.front());
        tracks.pop_front(), kept.pop_front(), ++moved;
      }
    }
    while (!tracks.empty()) write(tracks.front()), tracks.pop_front(), kept.pop_front();
    ASSERT_GT(moved, 100);
  }
  const test::CommandOutput r = test::run_command(std::string(GPILOT_BIN_DIR) + "/gpilot-replay " + late +
                                                  " --stage hands --check --config " + GPILOT_SOURCE_DIR +
                                                  "/deploy/config/synthetic.yaml 2>&1");
  std::filesystem::remove(late);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("HAND_OBS     new    167  recorded    167  differences 0"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace gpilot
