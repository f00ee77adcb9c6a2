// gpilot-tracker as a real process over real LCM (inside a private network namespace): a TRACKER_INIT box,
// then real frames on CAMERA; one USER_TRACK per good frame with its seq and utime, boxes identical to the
// core run in-process over the same frames; malformed CAMERA messages rejected (HEALTH) without a
// USER_TRACK and without advancing the track. After a reset, a frame with a face: the track it starts carries
// the face box the core finds.
#include <gtest/gtest.h>

#include <map>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bus_node.hpp"
#include "child_process.hpp"
#include "image_codec.hpp"
#include "sequence.hpp"
#include "user_tracker.hpp"

using namespace gpilot;

namespace {

const char* kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

}  // namespace

TEST(TrackerService, TracksRealFramesBySeqAndRejectsMalformedOnes) {
  std::vector<cv::Mat> frames;
  {
    auto src = open_otb(std::string(GPILOT_SOURCE_DIR) + "/data/tracking/cf_tracking_sample");
    EvalFrame f;
    while (src->next(f) && frames.size() < 16) frames.push_back(f.image.clone());
  }
  const cv::Rect2d init(261, 48, 39, 65);

  test::ChildProcess service({std::string(GPILOT_BIN_DIR) + "/gpilot-tracker", "--lcm-url", kUrl});
  ASSERT_GT(service.pid(), 0) << "cannot start gpilot-tracker";
  BusNode bus("test-tracker", kUrl);
  std::map<int64_t, user_track_t> tracks;
  health_t last_health{};
  bool heard = false;
  bus.subscribe<user_track_t>("USER_TRACK", [&](const user_track_t& m, int64_t) { tracks[m.seq] = m; });
  bus.subscribe<health_t>("HEALTH", [&](const health_t& m, int64_t) {
    if (m.name != "gpilot-tracker") return;
    last_health = m;
    heard = true;
  });
  auto spin_until = [&](const std::function<bool()>& done, int max_ms) {
    for (int waited = 0; waited < max_ms && !done(); waited += 20) bus.spin_once(20);
    return done();
  };
  ASSERT_TRUE(spin_until([&] { return heard; }, 10000)) << "no HEALTH from gpilot-tracker";

  // GIVEN a manual box, then frames 0..15 with two malformed CAMERA messages after frame 7
  tracker_init_t req{};
  const int64_t t0 = wall_utime();  // the bus rejects a utime far from its arrival
  req.utime = t0;
  req.seq = 1;
  req.command = tracker_init_t::COMMAND_SET_BOX;
  req.box[0] = static_cast<float>(init.x);
  req.box[1] = static_cast<float>(init.y);
  req.box[2] = static_cast<float>(init.width);
  req.box[3] = static_cast<float>(init.height);
  req.source = "test_lcm_tracker";
  bus.publish("TRACKER_INIT", req);
  bus.spin_once(100);
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
  UserTracker core{TrackerParams{}};
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
  reset.utime = wall_utime();
  reset.seq = 2;
  reset.command = tracker_init_t::COMMAND_RESET;
  reset.source = "test_lcm_tracker";
  bus.publish("TRACKER_INIT", reset);
  bus.spin_once(100);
  const cv::Mat a = cv::imread(std::string(GPILOT_SOURCE_DIR) + "/data/people/astronaut.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(a.empty());
  cv::Mat face_frame(360, 640, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::resize(a, face_frame(cv::Rect(140, 0, 360, 360)), cv::Size(360, 360), 0, 0, cv::INTER_AREA);
  bus.publish("CAMERA", mat_to_image(face_frame, t0 + 5000 + 33000 * 16, 16));
  ASSERT_TRUE(spin_until([&] { return tracks.count(16) > 0; }, 10000)) << "no USER_TRACK for the face frame";
  // THEN the face search starts a track, and USER_TRACK carries the face the core finds in that frame.
  core.reset();
  const TrackOutput want = core.process(face_frame);
  ASSERT_TRUE(want.face.has_value());
  const user_track_t& got = tracks[16];
  EXPECT_EQ(got.status, user_track_t::STATUS_TRACKING);
  EXPECT_EQ(got.init_source, user_track_t::INIT_FACE);
  EXPECT_EQ(got.track_id, 2);
  EXPECT_EQ(got.face_box[0], static_cast<float>(want.face->x));
  EXPECT_EQ(got.face_box[1], static_cast<float>(want.face->y));
  EXPECT_EQ(got.face_box[2], static_cast<float>(want.face->width));
  EXPECT_EQ(got.face_box[3], static_cast<float>(want.face->height));
  EXPECT_TRUE(cv::Rect2d(got.face_box[0], got.face_box[1], got.face_box[2], got.face_box[3]).contains({298, 81}));
}
