// gpilot-tracker as a real process over real LCM (inside a private network namespace): a TRACKER_INIT box,
// then real frames on CAMERA; one USER_TRACK per good frame with its seq and utime, boxes identical to the
// core run in-process over the same frames; malformed CAMERA messages rejected (HEALTH) without a
// USER_TRACK and without advancing the track. After a reset, a frame with a face: the track it starts carries
// the face box the core finds; a face with its body below the frame starts none and is counted in HEALTH.
// Under load (both cores busy) the stage skips frames, counts them, and its
// replay over the run's log agrees bit for bit.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>

#include <lcm/lcm-cpp.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bus_node.hpp"
#include "bus_params.hpp"
#include "child_process.hpp"
#include "image_codec.hpp"
#include "sequence.hpp"
#include "face_cascade.hpp"
#include "user_tracker.hpp"

using namespace gpilot;

namespace {

const char* kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

// gpilot-tracker as a real process and a test node on the bus beside it, keeping the stage's last HEALTH.
// wait_for_health() returns once the first HEALTH came (the stage is then listening).
struct TrackerUnderTest {
  explicit TrackerUnderTest(const std::string& node_name, const std::vector<std::string>& extra = {})
      : service(command(extra)), bus(node_name, kUrl) {
    bus.subscribe<health_t>("HEALTH", [this](const health_t& m, int64_t) {
      if (m.name != "gpilot-tracker") return;
      last_health = m;
      heard = true;
    });
  }
  bool spin_until(const std::function<bool()>& done, int max_ms) {
    for (int waited = 0; waited < max_ms && !done(); waited += 20) bus.spin_once(20);
    return done();
  }
  bool wait_for_health() { return spin_until([this] { return heard; }, 10000); }
  // Sends a TRACKER_INIT and returns once HEALTH counts it in. CAMERA comes on the frames' own socket, so a
  // frame sent right after it could be dispatched first. Call it with the stage idle.
  bool give(tracker_init_t req) {
    const int64_t report = last_health.seq;
    spin_until([&] { return last_health.seq > report; }, 3000);  // a count taken after all sent before
    const int64_t in = last_health.messages_in;
    req.utime = wall_utime();  // the bus rejects a utime far from its arrival
    bus.publish("TRACKER_INIT", req);
    return spin_until([&] { return last_health.messages_in > in; }, 5000);
  }

  static std::vector<std::string> command(const std::vector<std::string>& extra) {
    std::vector<std::string> argv{std::string(GPILOT_BIN_DIR) + "/gpilot-tracker", "--lcm-url", kUrl};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }

  test::ChildProcess service;
  BusNode bus;
  health_t last_health{};
  bool heard = false;
};

}  // namespace

TEST(TrackerService, TracksRealFramesBySeqAndRejectsMalformedOnes) {
  std::vector<cv::Mat> frames;
  {
    auto src = open_otb(std::string(GPILOT_SOURCE_DIR) + "/data/tracking/cf_tracking_sample");
    EvalFrame f;
    while (src->next(f) && frames.size() < 16) frames.push_back(f.image.clone());
  }
  const cv::Rect2d init(261, 48, 39, 65);

  TrackerUnderTest stage("test-tracker");
  ASSERT_GT(stage.service.pid(), 0) << "cannot start gpilot-tracker";
  BusNode& bus = stage.bus;
  const health_t& last_health = stage.last_health;
  const auto spin_until = [&stage](const std::function<bool()>& done, int max_ms) { return stage.spin_until(done, max_ms); };
  std::map<int64_t, user_track_t> tracks;
  bus.subscribe<user_track_t>("USER_TRACK", [&](const user_track_t& m, int64_t) { tracks[m.seq] = m; });
  ASSERT_TRUE(stage.wait_for_health()) << "no HEALTH from gpilot-tracker";

  // GIVEN a manual box, then frames 0..15 with two malformed CAMERA messages after frame 7
  tracker_init_t req{};
  req.seq = 1;
  req.command = tracker_init_t::COMMAND_SET_BOX;
  req.box[0] = static_cast<float>(init.x);
  req.box[1] = static_cast<float>(init.y);
  req.box[2] = static_cast<float>(init.width);
  req.box[3] = static_cast<float>(init.height);
  req.source = "test_lcm_tracker";
  ASSERT_TRUE(stage.give(req)) << "TRACKER_INIT not taken";
  const int64_t t0 = wall_utime();  // the bus rejects a utime far from its arrival
  auto send = [&](int64_t seq) {
    bus.publish("CAMERA", mat_to_image(frames[static_cast<size_t>(seq)], t0 + 5000 + 33000 * seq, seq));
    // One frame at a time: the answer comes before the next frame, so that no frame is dropped.
    spin_until([&] { return tracks.count(seq) > 0; }, 3000);
  };
  for (int64_t s = 0; s < 8; ++s) send(s);
  image_t bad = mat_to_image(frames[8], t0 + 999, 100, image_t::PIXEL_FORMAT_JPEG);
  for (size_t i = 0; i < bad.data.size(); i += 7) bad.data[i] = 0;  // not a JPEG any more
  bus.publish("CAMERA", bad);
  const uint8_t garbage[] = {1, 2, 3, 4, 5};
  bus.publish_raw("CAMERA", garbage, sizeof garbage);
  bus.spin_once(200);
  for (int64_t s = 8; s < 16; ++s) send(s);

  // THEN one USER_TRACK per good frame, with its seq and utime, none for the bad one
  ASSERT_TRUE(spin_until([&] { return tracks.size() >= 16; }, 5000)) << tracks.size() << " tracks";
  EXPECT_EQ(tracks.size(), 16u);
  EXPECT_EQ(tracks.count(100), 0u);
  // and the boxes are the core's over the good frames only (the bad ones did not advance the track).
  UserTracker core{TrackerParams{}, load_tracker_models(TrackerParams{})};
  core.set_box(init);
  for (int64_t s = 0; s < 16; ++s) {
    const TrackOutput want = core.process(frames[static_cast<size_t>(s)]);
    const user_track_t& got = tracks[s];
    EXPECT_EQ(got.utime, t0 + 5000 + 33000 * s);
    EXPECT_EQ(got.status, user_track_t::STATUS_TRACKING) << "seq " << s;
    EXPECT_EQ(got.init_source, user_track_t::INIT_MANUAL);
    EXPECT_EQ(got.track_id, 1);
    EXPECT_EQ(got.image_width, 640);
    EXPECT_EQ(got.image_height, 360);
    EXPECT_EQ(got.box[0], static_cast<float>(want.box.x)) << "seq " << s;
    EXPECT_EQ(got.box[1], static_cast<float>(want.box.y)) << "seq " << s;
    EXPECT_EQ(got.box[2], static_cast<float>(want.box.width)) << "seq " << s;
    EXPECT_EQ(got.confidence, static_cast<float>(want.confidence)) << "seq " << s;
    // No face looked for (manual start, no re-check within 16 frames): all zero.
    ASSERT_FALSE(want.face.has_value()) << "seq " << s;
    for (int k = 0; k < 4; ++k) EXPECT_EQ(got.face_box[k], 0.0f) << "seq " << s;
  }
  // AND HEALTH counts the two malformed messages.
  ASSERT_TRUE(spin_until([&] { return last_health.rejected >= 2 && last_health.messages_out >= 16; }, 5000))
      << "rejected " << last_health.rejected << " last reason: " << last_health.last_reject_reason;
  EXPECT_EQ(last_health.rejected, 2);

  // GIVEN a reset, WHEN a frame with a frontal face comes (the astronaut photograph in a 640x360 frame)
  tracker_init_t reset{};
  reset.seq = 2;
  reset.command = tracker_init_t::COMMAND_RESET;
  reset.source = "test_lcm_tracker";
  ASSERT_TRUE(stage.give(reset)) << "TRACKER_INIT reset not taken";
  const cv::Mat a = cv::imread(std::string(GPILOT_SOURCE_DIR) + "/data/people/astronaut.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(a.empty());
  cv::Mat face_frame(360, 640, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::resize(a, face_frame(cv::Rect(140, 0, 360, 360)), cv::Size(360, 360), 0, 0, cv::INTER_AREA);
  // (again and again: the face search spreads a scan of the frame over frames, face.scan_slice_pixels)
  core.reset();
  TrackOutput want;
  int64_t seq = 16;
  for (; seq < 16 + FaceDetector(TrackerParams{}, load_face_cascade(TrackerParams{})).scan_tiles(face_frame.size()); ++seq) {
    bus.publish("CAMERA", mat_to_image(face_frame, wall_utime(), seq));
    ASSERT_TRUE(spin_until([&] { return tracks.count(seq) > 0; }, 10000)) << "no USER_TRACK for the face frame " << seq;
    want = core.process(face_frame);
    EXPECT_EQ(tracks[seq].status, static_cast<int8_t>(want.status)) << "seq " << seq;
    if (want.status == TrackStatus::kTracking) break;
  }
  // THEN the face search starts a track, and USER_TRACK carries the face the core finds in that frame.
  ASSERT_TRUE(want.face.has_value());
  // (value_or: GCC 12 cannot see the assertion above and warns of an uninitialised read)
  const cv::Rect2d want_face = want.face.value_or(cv::Rect2d());
  const user_track_t& got = tracks[seq];
  EXPECT_EQ(got.status, user_track_t::STATUS_TRACKING);
  EXPECT_EQ(got.init_source, user_track_t::INIT_FACE);
  EXPECT_EQ(got.track_id, 2);
  EXPECT_EQ(got.face_box[0], static_cast<float>(want_face.x));
  EXPECT_EQ(got.face_box[1], static_cast<float>(want_face.y));
  EXPECT_EQ(got.face_box[2], static_cast<float>(want_face.width));
  EXPECT_EQ(got.face_box[3], static_cast<float>(want_face.height));
  EXPECT_TRUE(cv::Rect2d(got.face_box[0], got.face_box[1], got.face_box[2], got.face_box[3]).contains({298, 81}));
}

// A face whose body box lies below the frame starts no track: the stage keeps searching and HEALTH counts
// the refused faces by reason, as many as the core refuses over the same frames.
TEST(TrackerService, RefusedFacesAreCountedInHealth) {
  // GIVEN the top 120 rows of the astronaut photograph (360 px) at the bottom of a grey 640x360 frame
  const cv::Mat a = cv::imread(std::string(GPILOT_SOURCE_DIR) + "/data/people/astronaut.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(a.empty());
  cv::Mat shrunk;
  cv::resize(a, shrunk, cv::Size(360, 360), 0, 0, cv::INTER_AREA);
  cv::Mat frame(360, 640, CV_8UC3, cv::Scalar(90, 90, 90));
  shrunk(cv::Rect(0, 0, 360, 120)).copyTo(frame(cv::Rect(140, 240, 360, 120)));
  TrackerUnderTest stage("test-tracker-refusals");
  ASSERT_GT(stage.service.pid(), 0) << "cannot start gpilot-tracker";
  std::map<int64_t, user_track_t> tracks;
  stage.bus.subscribe<user_track_t>("USER_TRACK", [&](const user_track_t& m, int64_t) { tracks[m.seq] = m; });
  ASSERT_TRUE(stage.wait_for_health()) << "no HEALTH from gpilot-tracker";
  // WHEN two whole scans' worth of frames come, one at a time (raw BGR: the core below sees the same pixels)
  UserTracker core{TrackerParams{}, load_tracker_models(TrackerParams{})};
  const int frames = 2 * FaceDetector(TrackerParams{}, load_face_cascade(TrackerParams{})).scan_tiles(frame.size());
  for (int64_t seq = 0; seq < frames; ++seq) {
    stage.bus.publish("CAMERA", mat_to_image(frame, wall_utime(), seq));
    ASSERT_TRUE(stage.spin_until([&] { return tracks.count(seq) > 0; }, 5000)) << "no USER_TRACK for seq " << seq;
    EXPECT_EQ(tracks[seq].status, user_track_t::STATUS_SEARCHING) << "seq " << seq;
    core.process(frame);
  }
  // THEN HEALTH says why no track started, with the core's count
  const int64_t refused = core.refusals(FaceRefusal::kOffFrame);
  ASSERT_GE(refused, 2);
  const std::string want = "faces refused: " + std::to_string(refused) + " " + refusal_text(FaceRefusal::kOffFrame);
  EXPECT_TRUE(stage.spin_until([&] { return stage.last_health.state_detail.find(want) != std::string::npos; }, 3000))
      << "HEALTH state_detail: '" << stage.last_health.state_detail << "', want '" << want << "'";
  EXPECT_EQ(stage.last_health.state, health_t::STATE_DEGRADED);
}

// GIVEN gpilot-tracker with the person search (tracker.person.enabled) WHEN ten frames with nobody in them come
// THEN HEALTH says what the search did: the detector on one searching frame in five, 2 runs, none found.
TEST(TrackerService, ThePersonSearchsCostIsInHealth) {
  TrackerUnderTest stage("test-tracker-person", {"--set", "tracker.person.enabled=true"});
  ASSERT_GT(stage.service.pid(), 0) << "cannot start gpilot-tracker";
  std::map<int64_t, user_track_t> tracks;
  stage.bus.subscribe<user_track_t>("USER_TRACK", [&](const user_track_t& m, int64_t) { tracks[m.seq] = m; });
  ASSERT_TRUE(stage.wait_for_health()) << "no HEALTH from gpilot-tracker";
  const cv::Mat frame(480, 640, CV_8UC3, cv::Scalar(90, 90, 90));
  for (int64_t seq = 0; seq < 10; ++seq) {
    stage.bus.publish("CAMERA", mat_to_image(frame, wall_utime(), seq));
    ASSERT_TRUE(stage.spin_until([&] { return tracks.count(seq) > 0; }, 5000)) << "no USER_TRACK for seq " << seq;
    EXPECT_EQ(tracks[seq].status, user_track_t::STATUS_SEARCHING) << "seq " << seq;
  }
  const std::string want = "person search: 2 runs (1 searching frame in 5)";
  EXPECT_TRUE(stage.spin_until([&] { return stage.last_health.state_detail.find(want) != std::string::npos; }, 3000))
      << "HEALTH state_detail: '" << stage.last_health.state_detail << "', want '" << want << "'";
  EXPECT_NE(stage.last_health.state_detail.find("0 found, 0 not the user, 0 started"), std::string::npos)
      << stage.last_health.state_detail;
}

// GIVEN the person search on and its model missing WHEN gpilot-tracker starts THEN it stops before the bus with
// status 2 (a bad config), naming the file.
TEST(TrackerService, AMissingPersonModelStopsItBeforeTheBusNamingTheFile) {
  const std::string cmd = std::string(GPILOT_BIN_DIR) + "/gpilot-tracker --lcm-url '" + kUrl +
                          "' --set tracker.person.enabled=true --set tracker.person.models_dir=models/no-such-folder 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) out += buf;
  const int status = pclose(p);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << "status " << status << ": " << out;
  EXPECT_NE(out.find("models/no-such-folder/pose_detection.onnx"), std::string::npos) << out;
}

// Under load the live stage and its replay agree bit for bit. Both cores are kept busy beside gpilot-tracker
// while all 53 frames of cf_tracking_sample are sent at once: the stage queues at most tracker.camera_queue
// frames and LCM drops those that arrive while the queue is full, as many as the load makes it (no count is
// asserted: that is timing). Everything on the bus is logged; gpilot-replay --check over that log gives the stage exactly the
// frames it processed (those with a USER_TRACK) and must find no difference, and HEALTH.dropped counts the
// skipped frames.
TEST(TrackerService, LiveAndReplayAgreeUnderLoadWithSkippedFrames) {
  std::vector<cv::Mat> frames;
  {
    auto src = open_otb(std::string(GPILOT_SOURCE_DIR) + "/data/tracking/cf_tracking_sample");
    EvalFrame f;
    while (src->next(f)) frames.push_back(f.image.clone());
  }
  ASSERT_EQ(frames.size(), 53u);

  const std::string log_path = ::testing::TempDir() + "gpilot_tracker_load.lcmlog";
  std::remove(log_path.c_str());
  std::map<int64_t, user_track_t> tracks;
  health_t last_health{};
  {
    // The stage ends with this scope, before its log is replayed.
    TrackerUnderTest stage("test-tracker-load");
    ASSERT_GT(stage.service.pid(), 0) << "cannot start gpilot-tracker";
    BusNode& bus = stage.bus;
    const auto spin_until = [&stage](const std::function<bool()>& done, int max_ms) { return stage.spin_until(done, max_ms); };
    lcm::LogFile log(log_path, "w");
    ASSERT_TRUE(log.good());
    int64_t eventnum = 0;
    bus.subscribe_raw("CAMERA|TRACKER_INIT|USER_TRACK", [&](const std::string& ch, const void* data, size_t size, int64_t t) {
      lcm::LogEvent ev{};
      ev.eventnum = eventnum++;
      ev.timestamp = t;
      ev.channel = ch;
      ev.datalen = static_cast<int32_t>(size);
      ev.data = const_cast<void*>(data);
      log.writeEvent(&ev);
    });
    bus.subscribe<user_track_t>("USER_TRACK", [&](const user_track_t& m, int64_t) { tracks[m.seq] = m; });
    ASSERT_TRUE(stage.wait_for_health()) << "no HEALTH from gpilot-tracker";

    // GIVEN both cores busy
    std::atomic<bool> stop{false};
    std::vector<std::thread> busy;
    for (int i = 0; i < 2; ++i)
      busy.emplace_back([&stop] {
        volatile double x = 1.0;
        while (!stop.load(std::memory_order_relaxed)) x = x * 1.0000001 + 1e-9;
      });
    // WHEN a manual box, then every frame at once
    tracker_init_t req{};
    req.seq = 1;
    req.command = tracker_init_t::COMMAND_SET_BOX;
    req.box[0] = 261;
    req.box[1] = 48;
    req.box[2] = 39;
    req.box[3] = 65;
    req.source = "test_lcm_tracker";
    ASSERT_TRUE(stage.give(req)) << "TRACKER_INIT not taken";
    // The camera starts later than bus.time_window_s after the box: the replay judges the box at its arrival,
    // not at the frame it is given before (where the bus would call it stale).
    stage.spin_until([] { return false; }, static_cast<int>(BusParams{}.time_window_s * 1000) + 300);
    for (size_t i = 0; i < frames.size(); ++i) {
      // JPEG, as the camera of ./deploy/run: 53 raw frames at once would overflow the socket's buffer.
      bus.publish("CAMERA", mat_to_image(frames[i], wall_utime(), static_cast<int64_t>(i), image_t::PIXEL_FORMAT_JPEG));
      bus.spin_once(0);
    }
    // Until the stage has answered all it will (no new USER_TRACK for a second; LCM drops the frames that
    // arrive while the queue is full, so which ones it answers is the load's doing).
    for (size_t n = 0; n != tracks.size() || n == 0;) {
      n = tracks.size();
      spin_until([&] { return tracks.size() > n; }, 1000);
      if (n == 0 && tracks.empty()) break;
    }
    stop = true;
    for (auto& t : busy) t.join();
    ASSERT_FALSE(tracks.empty()) << "no USER_TRACK at all";
    spin_until([&] { return stage.last_health.messages_out >= static_cast<int64_t>(tracks.size()); }, 5000);
    last_health = stage.last_health;
  }
  // Skipped: the frames between the first and the last it processed that it never saw.
  const int64_t skipped = tracks.rbegin()->first - tracks.begin()->first + 1 - static_cast<int64_t>(tracks.size());
  std::printf("under load: %zu of 53 frames processed (seq %lld..%lld), %lld skipped between; HEALTH.dropped %lld\n",
              tracks.size(), static_cast<long long>(tracks.begin()->first), static_cast<long long>(tracks.rbegin()->first),
              static_cast<long long>(skipped), static_cast<long long>(last_health.dropped));
  // THEN HEALTH counts the skipped frames (the first frame finds the queue empty)
  EXPECT_EQ(tracks.count(0), 1u);
  EXPECT_EQ(last_health.dropped, skipped);
  // AND the replay of the stage over the log, given the frames the live stage processed, agrees bit for bit.
  test::ChildProcess replay({std::string(GPILOT_BIN_DIR) + "/gpilot-replay", log_path, "--stage", "tracker", "--check"});
  const int status = replay.wait();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "gpilot-replay --check found differences (status " << status << ")";
  // Given every frame instead (as before), the replay would follow another track.
  if (skipped > 0) {
    test::ChildProcess all({std::string(GPILOT_BIN_DIR) + "/gpilot-replay", log_path, "--stage", "tracker", "--check", "--all-frames"});
    const int st = all.wait();
    EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 1) << "--all-frames found no difference with frames skipped";
  }
  // The core in-process over the same frames says the same.
  UserTracker core{TrackerParams{}, load_tracker_models(TrackerParams{})};
  core.set_box(cv::Rect2d(261, 48, 39, 65));
  for (const auto& [seq, got] : tracks) {
    // The frame as the stage saw it: through the JPEG codec.
    cv::Mat seen;
    ASSERT_EQ(image_to_mat(mat_to_image(frames[static_cast<size_t>(seq)], 0, seq, image_t::PIXEL_FORMAT_JPEG), seen), "");
    const TrackOutput want = core.process(seen);
    EXPECT_EQ(got.box[0], static_cast<float>(want.box.x)) << "seq " << seq;
    EXPECT_EQ(got.box[1], static_cast<float>(want.box.y)) << "seq " << seq;
    EXPECT_EQ(got.confidence, static_cast<float>(want.confidence)) << "seq " << seq;
  }
  std::remove(log_path.c_str());
}
