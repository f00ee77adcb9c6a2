// The order gpilot-replay gives a stage inputs the log heard on two sockets, whatever order the recorder wrote
// them in. PairHold (tools/replay/pair_hold.hpp): known answers; and, on the committed hands log, GIVEN the log
// rewritten with every USER_TRACK 20 frames late (a tracker behind under load; the live pairer waits 15 seqs),
// or with every frame after its track (the recorder's frames socket served late) WHEN hands is replayed THEN
// every HAND_OBS is given again, unchanged. InitAlign (init_align.hpp): known answers; and GIVEN a tracker
// log with a manual box, rewritten with the TRACKER_INIT 3 frames after the frame it was started on WHEN the
// tracker is replayed THEN every USER_TRACK is given again, unchanged; the same for a RESET.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "gpilot/tracker_init_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "init_align.hpp"
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
                                                  "/deploy/config/synthetic-skin.yaml 2>&1");
  std::filesystem::remove(log);
  EXPECT_EQ(r.code, 0) << r.out;
  return r.out;
}

// What a replay of logs/hands.lcmlog in the recorded order gives: every recorded HAND_OBS, the same.
#define GPILOT_STR2(x) #x
#define GPILOT_STR(x) GPILOT_STR2(x)
const std::string kSameAsRecorded =
    "HAND_OBS     new    " GPILOT_STR(GPILOT_HANDS_LOG_OUTPUTS) "  recorded    " GPILOT_STR(GPILOT_HANDS_LOG_OUTPUTS) "  differences 0";

TEST(PairHold, HandsReplaysTheSamePairsWhenEveryTrackComesLate) {
  // 20 frames late: the live pairer (15 seqs) would have let each frame expire
  const std::string out = replay_hands(rewritten("USER_TRACK", 20));
  EXPECT_NE(out.find(kSameAsRecorded), std::string::npos) << out;
}

TEST(PairHold, HandsReplaysTheSamePairsWhenEveryFrameComesAfterItsTrack) {
  const std::string out = replay_hands(rewritten("CAMERA", 2));
  EXPECT_NE(out.find(kSameAsRecorded), std::string::npos) << out;
}

TEST(InitAlign, ASetBoxIsGivenBeforeTheFrameItsBoxWasStartedOn) {
  InitAlign a;
  const InitAlign::Box box{200, 100, 80, 200}, other{20, 10, 50, 100};
  for (int64_t s = 1; s <= 7; ++s) a.frame(s);
  a.set_box(box);      // logged after frame 7, started on frame 6 (the recorder heard it late)
  a.set_box(other);    // a box no track was started on (refused, or replaced before a frame came)
  a.manual_start(6, box);
  a.finish();
  ASSERT_TRUE(a.frame_of(0));
  EXPECT_EQ(*a.frame_of(0), 6);
  EXPECT_FALSE(a.frame_of(1));
  EXPECT_EQ(a.due_before(6), std::vector<size_t>{0});
  EXPECT_TRUE(a.due_before(7).empty());
}

TEST(InitAlign, TheSameBoxTwiceGoesToTheNearestStarts) {
  InitAlign a;
  const InitAlign::Box box{10, 10, 40, 90};
  a.frame(10);
  a.set_box(box);  // expected on 11
  a.frame(40);
  a.set_box(box);  // expected on 41
  a.manual_start(42, box);
  a.manual_start(11, {10, 10, 40, 80});  // cut by the frame's bottom: still inside the asked box
  a.finish();
  EXPECT_EQ(a.frame_of(0), std::optional<int64_t>(11));
  EXPECT_EQ(a.frame_of(1), std::optional<int64_t>(42));
}

// Copies `from` into `to`: the TRACKER_INIT `init` (if given) after the `after`-th CAMERA; the log's own
// TRACKER_INIT messages `late` CAMERA frames after where they were.
void copy_log(const std::string& from, const std::string& to, const tracker_init_t* init, int after, int late) {
  lcm::LogFile in(from, "r"), out(to, "w");
  ASSERT_TRUE(in.good() && out.good());
  int64_t eventnum = 0;
  int frames = 0;
  std::deque<std::pair<int, std::pair<lcm::LogEvent, std::vector<uint8_t>>>> held;  // due after frame n
  const auto write = [&](lcm::LogEvent e, const std::vector<uint8_t>* data) {
    e.eventnum = eventnum++;
    if (data) e.data = const_cast<uint8_t*>(data->data()), e.datalen = static_cast<int32_t>(data->size());
    out.writeEvent(&e);
  };
  for (const lcm::LogEvent* ev = in.readNextEvent(); ev; ev = in.readNextEvent()) {
    if (ev->channel == "TRACKER_INIT") {
      const auto* p = static_cast<const uint8_t*>(ev->data);
      held.push_back({frames + late, {*ev, std::vector<uint8_t>(p, p + ev->datalen)}});
      continue;
    }
    write(*ev, nullptr);
    if (ev->channel != "CAMERA") continue;
    ++frames;
    while (!held.empty() && held.front().first <= frames) {
      write(held.front().second.first, &held.front().second.second);
      held.pop_front();
    }
    if (init && frames == after) {
      tracker_init_t m = *init;
      m.utime = ev->timestamp;  // now on the log's clock: the bus refuses a message from another time
      std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
      m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
      lcm::LogEvent e = *ev;
      e.channel = "TRACKER_INIT";
      e.timestamp = ev->timestamp + 1;
      write(e, &bytes);
    }
  }
}

// GIVEN the committed tracker log with `init` after its 60th frame, and the tracker's outputs on it (which must
// show the init's effect: `acted`) WHEN the TRACKER_INIT is written 3 frames after the frame it took effect on
// and the tracker replayed THEN every USER_TRACK is the one the tracker gave with the init where it was.
void replays_an_init_written_three_frames_late(const tracker_init_t& init,
                                               const std::function<bool(const user_track_t& before, const user_track_t&)>& acted) {
  const std::string tmp = std::filesystem::temp_directory_path() / ("gpilot-init-" + std::to_string(getpid()));
  const std::string config = std::string(GPILOT_SOURCE_DIR) + "/deploy/config/synthetic-skin.yaml";
  const std::string replay = std::string(GPILOT_BIN_DIR) + "/gpilot-replay ";
  copy_log(std::string(GPILOT_SOURCE_DIR) + "/tests/replay/logs/tracker.lcmlog", tmp + "-a.lcmlog", &init, 60, 0);
  const test::CommandOutput made = test::run_command(replay + tmp + "-a.lcmlog --stage tracker --config " + config +
                                                     " --out " + tmp + "-b.lcmlog 2>&1");
  ASSERT_EQ(made.code, 0) << made.out;
  int effects = 0;
  {
    lcm::LogFile b(tmp + "-b.lcmlog", "r");
    user_track_t before{};
    for (const lcm::LogEvent* ev = b.readNextEvent(); ev; ev = b.readNextEvent()) {
      user_track_t t{};
      if (ev->channel != "USER_TRACK" || t.decode(ev->data, 0, ev->datalen) <= 0) continue;
      effects += acted(before, t);
      before = t;
    }
  }
  ASSERT_GT(effects, 0) << "the init did nothing visible: the test proves nothing";
  copy_log(tmp + "-b.lcmlog", tmp + "-c.lcmlog", nullptr, 0, 3);
  const test::CommandOutput r = test::run_command(replay + tmp + "-c.lcmlog --stage tracker --check --config " + config + " 2>&1");
  if (!::testing::Test::HasFailure())
    for (const char* s : {"-a.lcmlog", "-b.lcmlog", "-c.lcmlog"}) std::filesystem::remove(tmp + s);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\n0 differences"), std::string::npos) << r.out;
}

TEST(InitAlign, TheTrackerReplaysAManualBoxTheLogHasThreeFramesLate) {
  tracker_init_t init{};
  init.seq = 1;
  init.command = tracker_init_t::COMMAND_SET_BOX;
  init.box[0] = 200, init.box[1] = 100, init.box[2] = 80, init.box[3] = 200;
  init.source = "test";
  replays_an_init_written_three_frames_late(init, [](const user_track_t&, const user_track_t& t) {
    return t.init_source == user_track_t::INIT_MANUAL && std::abs(t.box[0] - 200.0f) < 1.0f;
  });
}

TEST(InitAlign, TheTrackerReplaysAResetTheLogHasThreeFramesLate) {
  tracker_init_t init{};
  init.seq = 1;
  init.command = tracker_init_t::COMMAND_RESET;
  init.source = "test";
  replays_an_init_written_three_frames_late(init, [](const user_track_t& before, const user_track_t& t) {
    return before.status == user_track_t::STATUS_TRACKING &&
           (t.status != user_track_t::STATUS_TRACKING || t.track_id != before.track_id);
  });
}

TEST(InitAlign, AResetIsGivenBeforeTheFrameTheTrackWasDroppedOn) {
  InitAlign a;
  for (int64_t s = 1; s <= 9; ++s) a.frame(s);
  a.reset();            // logged after frame 9, acted on frame 7
  a.dropped(7);
  a.dropped(40);        // another drop, too far
  a.frame(60);
  a.reset();            // logged after 60: no drop within 10 frames
  a.finish();
  EXPECT_EQ(a.frame_of(0), std::optional<int64_t>(7));
  EXPECT_FALSE(a.frame_of(1));
}

}  // namespace
}  // namespace gpilot
