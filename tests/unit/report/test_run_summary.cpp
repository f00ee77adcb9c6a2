// gpilot-report's numbers on a synthetic run with known counts, latencies, rates and accuracy.
#include <gtest/gtest.h>

#include "analyze_log.hpp"
#include "tool_test_helpers.hpp"

namespace gpilot {
namespace {

// The default synthetic run: 100 frames at 25 Hz; expected FINE for seq 0..49, CLOSER for 50..99; decided
// HOVER 0..30, FINE 31..80 (UP at 40), CLOSER 81..99 (FURTHER at 90); GESTURE_CMD 70 + seq % 10 ms after
// the frame's utime, FLIGHT_SETPOINT 5 ms later; CAMERA received 1 ms after its utime.
// The paper's rule with this buffer size ("paper"), or the evidence rule ("evidence").
Summary analyse(const test::SyntheticRun& run, int buffer_size, std::vector<TrajectoryPoint>* path = nullptr,
                const std::string& rule = "paper") {
  const test::ScratchDir dir("gpilot_run_summary");
  test::write_synthetic_log(dir / "run.lcmlog", run);
  LogAnalysis a = analyse_log(dir / "run.lcmlog", settling_for(rule, buffer_size));
  EXPECT_TRUE(a.warnings.empty()) << (a.warnings.empty() ? "" : a.warnings[0]);
  if (path) *path = a.path;
  return a.summary;
}

class RunSummaryTest : public ::testing::Test {
 protected:
  void SetUp() override { run.size = cv::Size(32, 24); }
  test::SyntheticRun run;
};

TEST_F(RunSummaryTest, CountsFramesCommandsAndTrack) {
  const Summary s = analyse(run, 60);
  EXPECT_EQ(s.frames, 100);
  EXPECT_NEAR(s.duration_s, 3.96, 1e-9);
  EXPECT_NEAR(s.camera_hz, 25.0, 1e-9);
  EXPECT_EQ(s.commands, 100);
  EXPECT_EQ(s.commands_by_mode[gesture_cmd_t::MODE_HOVER], 31);
  EXPECT_EQ(s.commands_by_mode[gesture_cmd_t::MODE_FINE], 49);
  EXPECT_EQ(s.commands_by_mode[gesture_cmd_t::MODE_UP], 1);
  EXPECT_EQ(s.commands_by_mode[gesture_cmd_t::MODE_DOWN], 0);
  EXPECT_EQ(s.commands_by_mode[gesture_cmd_t::MODE_CLOSER], 18);
  EXPECT_EQ(s.commands_by_mode[gesture_cmd_t::MODE_FURTHER], 1);
  EXPECT_EQ(s.track_by_status[user_track_t::STATUS_TRACKING], 100);
  EXPECT_EQ(s.track_turned_away, 0);
  EXPECT_EQ(s.vehicle_states, 100);
}

TEST_F(RunSummaryTest, CountsTheTrackingFramesWithTheUserTurnedAway) {
  run.facing = [](int64_t seq) { return seq >= 60 && seq < 75 ? user_track_t::FACING_AWAY : user_track_t::FACING_TOWARD; };
  EXPECT_EQ(analyse(run, 60).track_turned_away, 15);
}

TEST_F(RunSummaryTest, LatenciesAreReceiptMinusFrameTimeMatchedBySeq) {
  const Summary s = analyse(run, 60);
  // 70..79 ms, ten of each: nearest-rank median 74, p95 79.
  EXPECT_EQ(s.latency_cmd.n, 100);
  EXPECT_DOUBLE_EQ(s.latency_cmd.median_ms, 74.0);
  EXPECT_DOUBLE_EQ(s.latency_cmd.p95_ms, 79.0);
  EXPECT_DOUBLE_EQ(s.latency_setpoint.median_ms, 79.0);
  EXPECT_DOUBLE_EQ(s.latency_setpoint.p95_ms, 84.0);
  EXPECT_DOUBLE_EQ(s.pipeline_cmd.median_ms, 73.0);  // CAMERA is received 1 ms after the frame's utime
  EXPECT_EQ(s.unmatched_commands, 0);
}

TEST_F(RunSummaryTest, StageRatesAndProcessingTimesFromHealth) {
  const Summary s = analyse(run, 60);
  ASSERT_EQ(s.stages.size(), 2u);
  EXPECT_EQ(s.stages[1].name, "gpilot-tracker");
  const StageHealth& h = s.stages[1];
  EXPECT_EQ(h.reports, 4);
  EXPECT_FLOAT_EQ(h.rate_out_last_hz, 26.0);    // reports: 0 (no period), 24, 25, 26
  EXPECT_FLOAT_EQ(h.rate_out_median_hz, 25.0);
  EXPECT_FLOAT_EQ(h.processing_p50_ms, 3.0);    // p50s 2, 3, 4, 5: nearest-rank median 3
  EXPECT_FLOAT_EQ(h.processing_p99_ms, 11.0);   // p99s 10..13
  EXPECT_FLOAT_EQ(h.processing_p99_max_ms, 13.0);
  // CPU 0.5 s at the first report (after frame 24) and 0.68 s at the last (after frame 99): 180 ms over the 75
  // frames received between them (25..99), in 75 x 40 ms = 3 s
  EXPECT_NEAR(h.cpu_ms_per_frame, 2.4, 1e-9);
  EXPECT_NEAR(h.cpu_percent, 6.0, 1e-9);
}

TEST_F(RunSummaryTest, AccuracySkipsTheSettlingFramesAfterEachChange) {
  // buffer 60: settle 31 frames; counted seq 31..49 (FINE) and 81..99 (CLOSER), one error in each.
  const Summary s = analyse(run, 60);
  const Accuracy& a = s.accuracy;
  EXPECT_EQ(a.settle_frames, 31);
  EXPECT_EQ(a.truth_frames, 100);
  EXPECT_EQ(a.frames_with_command, 100);
  EXPECT_EQ(a.skipped_settling, 62);
  EXPECT_EQ(a.evaluated, 38);
  EXPECT_EQ(a.correct, 36);
  EXPECT_NEAR(a.value(), 36.0 / 38.0, 1e-12);
  EXPECT_EQ(a.confusion[gesture_cmd_t::MODE_FINE][gesture_cmd_t::MODE_FINE], 18);
  EXPECT_EQ(a.confusion[gesture_cmd_t::MODE_FINE][gesture_cmd_t::MODE_UP], 1);
  EXPECT_EQ(a.confusion[gesture_cmd_t::MODE_CLOSER][gesture_cmd_t::MODE_CLOSER], 18);
  EXPECT_EQ(a.confusion[gesture_cmd_t::MODE_CLOSER][gesture_cmd_t::MODE_FURTHER], 1);
  EXPECT_NE(a.rule.find("31 frames"), std::string::npos) << a.rule;
}

TEST_F(RunSummaryTest, AShorterBufferCountsTheLagAsErrors) {
  // buffer 20: settle 11; counted 11..49 and 61..99: HOVER 11..30 and FINE 61..80 are now wrong.
  const Summary s = analyse(run, 20);
  EXPECT_EQ(s.accuracy.evaluated, 78);
  EXPECT_EQ(s.accuracy.correct, 36);
  EXPECT_EQ(s.accuracy.confusion[gesture_cmd_t::MODE_FINE][gesture_cmd_t::MODE_HOVER], 20);
  EXPECT_EQ(s.accuracy.confusion[gesture_cmd_t::MODE_CLOSER][gesture_cmd_t::MODE_FINE], 20);
}

TEST_F(RunSummaryTest, TheEvidenceRuleIsJudgedFromEightTenthsOfASecondAfterEachChange) {
  // 0.8 s at 25 Hz: counted seq 20..49 and 70..99. HOVER 20..30 and FINE 70..80 are wrong (the reaction the
  // paper's settling hid), the UP at 40 and the FURTHER at 90 as before.
  const Summary s = analyse(run, 60, nullptr, "evidence");
  const Accuracy& a = s.accuracy;
  EXPECT_EQ(a.settle_frames, 0);
  EXPECT_DOUBLE_EQ(a.settle_s, 0.8);
  EXPECT_EQ(a.skipped_settling, 40);
  EXPECT_EQ(a.evaluated, 60);
  EXPECT_EQ(a.correct, 36);
  EXPECT_EQ(a.confusion[gesture_cmd_t::MODE_FINE][gesture_cmd_t::MODE_HOVER], 11);
  EXPECT_EQ(a.confusion[gesture_cmd_t::MODE_CLOSER][gesture_cmd_t::MODE_FINE], 11);
  EXPECT_NE(a.rule.find("0.8 s (decide.rule evidence"), std::string::npos) << a.rule;
}

TEST_F(RunSummaryTest, ReactionScoresEveryFrameJoinedBySeq) {
  // The synthetic truth says REST throughout (its gesture field is 0): every command that is not HOVER and not
  // the frame's expected mode (FINE before frame 50, CLOSER from it) is a motion asked while resting. Episodes:
  // UP 40, FINE 50..80, FURTHER 90: 3 of them, 33 frames (FINE 31..49 and CLOSER 81..99 are what the true hands
  // show); 69 frames differ from the truth's HOVER; no change to react to.
  const Summary s = analyse(run, 60);
  EXPECT_EQ(s.reaction.frames, 100);
  EXPECT_EQ(s.reaction.changes, 0);
  EXPECT_EQ(s.reaction.false_at_rest, 3);
  EXPECT_EQ(s.reaction.false_at_rest_frames, 33);
  EXPECT_EQ(s.reaction.wrong_frames, 69);
  EXPECT_EQ(summary_json(s)["gesture_reaction"]["changes"], 0);
  EXPECT_EQ(summary_json(s)["gesture_reaction"]["false_at_rest"], 3);
}

TEST_F(RunSummaryTest, NoTruthNoAccuracy) {
  run.with_truth = false;
  const Summary s = analyse(run, 60);
  EXPECT_FALSE(s.accuracy.has_value());
  EXPECT_EQ(s.accuracy.truth_frames, 0);
  const json j = summary_json(s);
  EXPECT_TRUE(j["gesture_accuracy"]["accuracy"].is_null()) << j.dump(2);
  EXPECT_TRUE(j["gesture_accuracy"]["accuracy_percent"].is_null());
}

TEST_F(RunSummaryTest, TrajectoryCarriesTheModeInForceAndTheUser) {
  std::vector<TrajectoryPoint> path;
  analyse(run, 60, &path);
  ASSERT_EQ(path.size(), 100u);
  // VEHICLE_STATE of frame k is received 10 ms after the frame, GESTURE_CMD 70..79 ms after: the mode in
  // force then is the one of frame k - 2 (its command came at k*40 - 80 + 70..79 < k*40 + 10).
  EXPECT_EQ(path[0].mode, -1);
  EXPECT_EQ(path[1].mode, -1);
  EXPECT_EQ(path[2].mode, gesture_cmd_t::MODE_HOVER);
  EXPECT_EQ(path[42].mode, gesture_cmd_t::MODE_UP);      // frame 40's command
  EXPECT_EQ(path[60].mode, gesture_cmd_t::MODE_FINE);
  EXPECT_EQ(path[99].mode, gesture_cmd_t::MODE_CLOSER);
  EXPECT_NEAR(path[50].north, 5.0, 1e-5);
  EXPECT_NEAR(path[50].t_s, 2.0, 1e-9);
  EXPECT_TRUE(path[50].has_person);
  EXPECT_DOUBLE_EQ(path[50].person_north, 10.0);
  EXPECT_DOUBLE_EQ(path[50].person_east, 2.0);
}

TEST(RunSummaryJson, IsOneObjectWithTheKeysTheLeadReads) {
  RunAnalyzer a(settling_for("paper", 60));
  const json j = summary_json(a.summary(), {{"log", "a \"b\"\n"}});
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.begin().key(), "log");  // the extra members come first
  for (const char* key : {"frames", "commands", "stages", "latency_ms", "gesture_accuracy", "vehicle", "log_gaps"})
    EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key : {"accuracy", "rule", "confusion"}) EXPECT_TRUE(j["gesture_accuracy"].contains(key)) << key;
  // The log's name escaped in the text and read back unchanged.
  const std::string text = j.dump(2);
  EXPECT_NE(text.find("\"log\": \"a \\\"b\\\"\\n\""), std::string::npos) << text;
  EXPECT_EQ(json::parse(text)["log"], "a \"b\"\n");
}

// The track against the truth, and both per range band (issue 13). GIVEN 40 frames, the user's true box
// 100x200 at (100, 50) and the drone 4 m from the user on frames 0..19, 9 m on 20..39; the track on the user
// (IoU 1) on 0..9, shifted by half its width (IoU 1/3) on 10..19, on a bystander beside (IoU 0) on 20..29 and
// LOST on 30..39 (the user out of view on 39); commands right on every frame but 25..39 WHEN summarised (buffer 2: 2 settling frames)
// THEN the counts and IoUs per band are those.
TEST(RunSummaryTrack, IouWithTheTrueBoxAndAccuracyPerRangeBand) {
  RunAnalyzer a(settling_for("paper", 2));
  for (int64_t seq = 0; seq < 40; ++seq) {
    ground_truth_t g{};
    g.seq = seq;
    g.utime = 1000 + seq;
    const float box[4] = {100, 50, 100, 200};
    std::copy(box, box + 4, g.user_box);
    g.expected_mode = gesture_cmd_t::MODE_HOVER;
    g.person_position[0] = seq < 20 ? 4.0f : 9.0f;
    g.camera_position[1] = 0.0f;
    a.on_truth(g, g.utime);
    user_track_t t{};
    t.seq = seq;
    t.utime = g.utime;
    t.status = seq < 30 ? user_track_t::STATUS_TRACKING : user_track_t::STATUS_LOST;
    t.image_width = 640;
    t.image_height = seq == 39 ? 100 : 480;  // frame 39: the user's box centre (150, 150) is out of view
    const float dx = seq < 10 ? 0.0f : seq < 20 ? 50.0f : 300.0f;
    const float tb[4] = {100 + dx, 50, 100, 200};
    std::copy(tb, tb + 4, t.box);
    a.on_track(t, t.utime);
    gesture_cmd_t c{};
    c.seq = seq;
    c.mode = seq >= 25 ? gesture_cmd_t::MODE_UP : gesture_cmd_t::MODE_HOVER;
    a.on_command(c, g.utime + 10);
  }
  const Summary s = a.summary();
  const TrackVsTruth& t = s.track_vs_truth;
  EXPECT_EQ(t.frames, 39);
  EXPECT_EQ(t.tracking, 30);
  EXPECT_EQ(t.on_user, 10);
  EXPECT_EQ(t.elsewhere, 10);
  EXPECT_NEAR(t.mean_iou(), (10 * 1.0 + 10 / 3.0) / 30, 1e-9);
  EXPECT_NEAR(t.iou_min, 0.0, 1e-12);
  ASSERT_EQ(s.range_bands.size(), 5u);
  const RangeBand& near = s.range_bands[1];  // 3-5 m
  EXPECT_EQ(near.truth_frames, 20);
  EXPECT_EQ(near.evaluated, 18);  // the first 2 settle
  EXPECT_EQ(near.correct, 18);
  EXPECT_EQ(near.track.on_user, 10);
  EXPECT_NEAR(near.track.mean_iou(), (1.0 + 1 / 3.0) / 2, 1e-9);
  const RangeBand& far = s.range_bands[3];  // 8-10 m
  EXPECT_EQ(far.truth_frames, 20);
  EXPECT_EQ(far.evaluated, 20);
  EXPECT_EQ(far.correct, 5);  // 20..24
  EXPECT_EQ(far.track.frames, 19);
  EXPECT_EQ(far.track.tracking, 10);
  EXPECT_EQ(far.track.elsewhere, 10);
  EXPECT_EQ(s.range_bands[0].truth_frames + s.range_bands[2].truth_frames + s.range_bands[4].truth_frames, 0);
  const json j = summary_json(s);
  EXPECT_EQ(j["track_vs_truth"]["on_user"], 10);
  ASSERT_EQ(j["range_bands"]["bands"].size(), 2u);  // the empty bands are left out
  EXPECT_EQ(j["range_bands"]["bands"][1]["from_m"], 8);
  EXPECT_EQ(j["range_bands"]["bands"][1]["accuracy_percent"], 25);
  EXPECT_NE(summary_table(s).find("8-10"), std::string::npos) << summary_table(s);
}

// The log's losses: gaps in seq per publisher's stream. GIVEN known gaps WHEN summarised THEN counted per
// channel; only counter channels (one message per seq) make the logger's loss; a restart is a new stream.
TEST(RunSummaryGaps, MessagesMissingFromTheLogPerChannel) {
  RunAnalyzer a(settling_for("paper", 60));
  auto camera = [&](int64_t seq) {
    image_t m{};
    m.seq = seq;
    m.utime = 1000 + seq;
    a.on_camera(m, 2000 + seq);
  };
  for (int64_t seq : {0, 1, 2, 5, 6, 8, 9}) camera(seq);  // 3, 4 and 7 lost
  for (int64_t seq : {0, 1, 2}) camera(seq);              // capture restarted: a new stream, no gap
  auto health = [&](const char* name, int32_t pid, int64_t seq) {
    health_t h{};
    h.name = name;
    h.pid = pid;
    h.seq = seq;
    a.on_health(h, 0);
  };
  health("gpilot-tracker", 10, 0);
  health("gpilot-hands", 20, 0);  // another process between the tracker's reports: not a gap
  health("gpilot-tracker", 10, 1);
  health("gpilot-tracker", 10, 3);  // 2 lost
  health("gpilot-tracker", 11, 0);  // restarted
  health("gpilot-tracker", 11, 1);
  health("gpilot-hands", 20, 1);
  for (int64_t seq : {0, 1, 2, 5}) {  // 3, 4: skipped by the tracker, or lost
    user_track_t t{};
    t.seq = seq;
    a.on_track(t, 0);
  }
  for (int64_t seq : {1, 3, 4}) {
    vehicle_state_t v{};
    v.seq = seq;
    a.on_vehicle(v, 0);
  }
  const Summary s = a.summary();
  ASSERT_EQ(s.gaps.count("CAMERA"), 1u);
  EXPECT_EQ(s.gaps.at("CAMERA").messages, 10);
  EXPECT_EQ(s.gaps.at("CAMERA").missing, 3);
  EXPECT_EQ(s.gaps.at("CAMERA").streams, 2);
  EXPECT_TRUE(s.gaps.at("CAMERA").counter);
  EXPECT_EQ(s.gaps.at("HEALTH").messages, 7);
  EXPECT_EQ(s.gaps.at("HEALTH").missing, 1);
  EXPECT_EQ(s.gaps.at("HEALTH").streams, 3);
  EXPECT_EQ(s.gaps.at("USER_TRACK").missing, 2);
  EXPECT_FALSE(s.gaps.at("USER_TRACK").counter);
  EXPECT_EQ(s.gaps.at("VEHICLE_STATE").missing, 1);
  EXPECT_EQ(s.logger_lost(), 3 + 1 + 1);  // not USER_TRACK's 2

  const json j = summary_json(s)["log_gaps"];
  EXPECT_EQ(j["logger_lost"], 5) << j.dump(2);
  EXPECT_EQ(j["channels"]["CAMERA"],
            json({{"messages", 10}, {"missing", 3}, {"streams", 2}, {"a_gap_is", "lost by the logger"}}))
      << j.dump(2);
  const std::string t = summary_table(s);
  EXPECT_NE(t.find("5 lost by the logger; CAMERA 3/13"), std::string::npos) << t;
  EXPECT_NE(t.find("USER_TRACK 2/6*"), std::string::npos) << t;
}

TEST(RunSummaryGaps, NoGapsNoLoss) {
  RunAnalyzer a(settling_for("paper", 60));
  for (int64_t seq = 0; seq < 5; ++seq) {
    image_t m{};
    m.seq = seq;
    a.on_camera(m, 0);
  }
  const Summary s = a.summary();
  EXPECT_EQ(s.gaps.at("CAMERA").missing, 0);
  EXPECT_EQ(s.logger_lost(), 0);
  EXPECT_EQ(summary_json(s)["log_gaps"]["logger_lost"], 0);
}

}  // namespace
}  // namespace gpilot
