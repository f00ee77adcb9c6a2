// PairHold (tools/replay/pair_hold.hpp): which order a pairing stage is given its two inputs. Known answers
// of the class; and, on the committed hands log, a replay that does not depend on the order the log heard
// CAMERA and USER_TRACK in: GIVEN the log rewritten with every USER_TRACK 20 frames late (a tracker behind
// under load; the live pairer waits 15 seqs), or with every frame after its track (the recorder's frames
// socket served late) WHEN hands is replayed THEN every HAND_OBS is given again, unchanged.
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

TEST(PairHold, APairIsGivenWhenItsSecondHalfComesFrameFirst) {
  PairHold h("CAMERA", "USER_TRACK");
  EXPECT_TRUE(h.pairs("CAMERA"));
  EXPECT_TRUE(h.pairs("USER_TRACK"));
  EXPECT_FALSE(h.pairs("TRACKER_INIT"));
  // Frame 1, then its track: the pair, frame first, each with its own time.
  EXPECT_TRUE(h.add("CAMERA", 1, 100, bytes(1)).empty());
  auto pair = h.add("USER_TRACK", 1, 130, bytes(11));
  ASSERT_EQ(pair.size(), 2u);
  EXPECT_EQ(pair[0].channel, "CAMERA");
  EXPECT_EQ(pair[0].timestamp, 100);
  EXPECT_EQ(pair[0].bytes, bytes(1));
  EXPECT_EQ(pair[1].channel, "USER_TRACK");
  EXPECT_EQ(pair[1].bytes, bytes(11));
  // A track heard before its frame (the recorder timestamped the frame late): still frame first.
  EXPECT_TRUE(h.add("USER_TRACK", 2, 170, bytes(12)).empty());
  pair = h.add("CAMERA", 2, 175, bytes(2));
  ASSERT_EQ(pair.size(), 2u);
  EXPECT_EQ(pair[0].channel, "CAMERA");
  EXPECT_EQ(pair[1].channel, "USER_TRACK");
  EXPECT_EQ(h.waiting(), 0u);
}

TEST(PairHold, AHalfThatNeverMeetsItsPartnerIsDroppedWhenALaterPairCompletes) {
  PairHold h("CAMERA", "USER_TRACK");
  h.add("CAMERA", 3, 0, bytes(3));       // its track never comes (the live tracker skipped it)
  h.add("USER_TRACK", 4, 0, bytes(14));  // its frame never comes (the live hands stage skipped it)
  h.add("CAMERA", 5, 0, bytes(5));
  EXPECT_EQ(h.waiting(), 3u);
  EXPECT_EQ(h.add("USER_TRACK", 5, 0, bytes(15)).size(), 2u);
  EXPECT_EQ(h.waiting(), 0u);
  EXPECT_EQ(h.never_paired(), 2);
  // A restarted capture's low seqs are not dropped by the old stream's later pairs.
  h.add("CAMERA", 2, 0, bytes(9));
  h.add("CAMERA", 5000, 0, bytes(9));
  EXPECT_EQ(h.add("USER_TRACK", 5000, 0, bytes(9)).size(), 2u);
  EXPECT_EQ(h.add("USER_TRACK", 2, 0, bytes(9)).size(), 2u);
}

// The committed hands log rewritten with every message of `late` given `by` frames (CAMERA) or tracks
// (USER_TRACK) of the other channel later.
std::string rewritten(const std::string& late, size_t by) {
  const std::string log = std::string(GPILOT_SOURCE_DIR) + "/tests/replay/logs/hands.lcmlog";
  const std::string path = std::filesystem::temp_directory_path() /
                           ("gpilot-late-" + late + "-" + std::to_string(getpid()) + ".lcmlog");
  const std::string other = late == "CAMERA" ? "USER_TRACK" : "CAMERA";
  lcm::LogFile in(log, "r"), out(path, "w");
  EXPECT_TRUE(in.good() && out.good());
  std::deque<lcm::LogEvent> held;  // copies whose data lives in `kept`
  std::deque<std::vector<uint8_t>> kept;
  int64_t eventnum = 0, moved = 0;
  const auto write = [&](lcm::LogEvent e) {
    e.eventnum = eventnum++;
    out.writeEvent(&e);
  };
  for (const lcm::LogEvent* ev = in.readNextEvent(); ev; ev = in.readNextEvent()) {
    if (ev->channel == late) {
      const auto* p = static_cast<const uint8_t*>(ev->data);
      kept.emplace_back(p, p + ev->datalen);
      held.push_back(*ev);
      held.back().data = kept.back().data();
      continue;
    }
    write(*ev);
    if (ev->channel == other && held.size() > by) write(held.front()), held.pop_front(), kept.pop_front(), ++moved;
  }
  while (!held.empty()) write(held.front()), held.pop_front(), kept.pop_front();
  EXPECT_GT(moved, 100);
  return path;
}

std::string replay_hands(const std::string& log) {
  const test::CommandOutput r = test::run_command(std::string(GPILOT_BIN_DIR) + "/gpilot-replay " + log +
                                                  " --stage hands --check --config " + GPILOT_SOURCE_DIR +
                                                  "/deploy/config/synthetic.yaml 2>&1");
  std::filesystem::remove(log);
  EXPECT_EQ(r.code, 0) << r.out;
  return r.out;
}

TEST(PairHold, HandsReplaysTheSamePairsWhenEveryTrackComesLate) {
  // 20 frames late: the live pairer (15 seqs) would have let each frame expire
  const std::string out = replay_hands(rewritten("USER_TRACK", 20));
  EXPECT_NE(out.find("HAND_OBS     new    167  recorded    167  differences 0"), std::string::npos) << out;
}

TEST(PairHold, HandsReplaysTheSamePairsWhenEveryFrameComesAfterItsTrack) {
  const std::string out = replay_hands(rewritten("CAMERA", 2));
  EXPECT_NE(out.find("HAND_OBS     new    167  recorded    167  differences 0"), std::string::npos) << out;
}

}  // namespace
}  // namespace gpilot
