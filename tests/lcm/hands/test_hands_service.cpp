// gpilot-hands as a real process over real LCM (run inside a private network namespace): CAMERA + USER_TRACK
// in, HAND_OBS out with the frame's seq; a track without its frame and a frame without its track are dropped
// and counted in HEALTH, never paired with another seq; a track made on another frame size is rejected.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include <opencv2/imgproc.hpp>

#include "bus_node.hpp"
#include "child_process.hpp"
#include "image_codec.hpp"
#include "user_track_fixture.hpp"

using namespace gpilot;

namespace {

const char* kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

// A blue frame with a skin-coloured person in the box (100, 100, 80, 160) and the right arm stretched out
// to the image's left (as in the unit test of the detector).
cv::Mat person_pointing() {
  const cv::Scalar skin(90, 120, 170), blue(200, 60, 20);
  cv::Mat frame(400, 400, CV_8UC3, blue);
  cv::rectangle(frame, cv::Rect(125, 100, 30, 32), skin, cv::FILLED);
  cv::rectangle(frame, cv::Rect(102, 160, 10, 12), skin, cv::FILLED);
  cv::rectangle(frame, cv::Rect(30, 125, 12, 12), skin, cv::FILLED);
  return frame;
}

// The messages' times: now (the bus rejects a utime far from its arrival).
int64_t t0() {
  static const int64_t start = wall_utime();
  return start;
}

user_track_t track(int64_t seq, int8_t status = user_track_t::STATUS_TRACKING) {
  return test::user_track_400(seq, t0() + seq, status);
}

}  // namespace

TEST(HandsService, PairsBySeqAndCountsTheUnmatched) {
  test::ChildProcess service(
      {std::string(GPILOT_BIN_DIR) + "/gpilot-hands", "--lcm-url", kUrl, "--set", "hands.match_window=3", "--set", "hands.method=skin"});
  ASSERT_GT(service.pid(), 0) << "cannot start gpilot-hands";
  BusNode bus("test-hands", kUrl);
  std::map<int64_t, hand_obs_t> obs;
  health_t last_health{};
  bool heard = false;
  bus.subscribe<hand_obs_t>("HAND_OBS", [&](const hand_obs_t& m, int64_t) { obs[m.seq] = m; });
  bus.subscribe<health_t>("HEALTH", [&](const health_t& m, int64_t) {
    if (m.name != "gpilot-hands") return;
    last_health = m;
    heard = true;
  });
  auto spin_until = [&](const std::function<bool()>& done, int max_ms) {
    for (int waited = 0; waited < max_ms && !done(); waited += 20) bus.spin_once(20);
    return done();
  };
  // GIVEN the service is up (its first HEALTH arrived).
  ASSERT_TRUE(spin_until([&] { return heard; }, 10000)) << "no HEALTH from gpilot-hands";

  const image_t frame = mat_to_image(person_pointing(), 0, 0);
  auto send_frame = [&](int64_t seq) {
    image_t f = frame;
    f.seq = seq;
    f.utime = t0() + seq;
    bus.publish("CAMERA", f);
    bus.spin_once(15);
  };
  auto send_track = [&](const user_track_t& t) {
    bus.publish("USER_TRACK", t);
    bus.spin_once(15);
  };
  // WHEN pairs 0..3 arrive (seq 2 track first), seq 4 with a SEARCHING track, a lone track 10 followed by
  // pairs 11..14, and a lone frame 20 followed by pairs 21..24 (window 3).
  for (int64_t s = 0; s <= 3; ++s) {
    if (s == 2) {
      send_track(track(s));
      send_frame(s);
    } else {
      send_frame(s);
      send_track(track(s));
    }
  }
  send_frame(4);
  send_track(track(4, user_track_t::STATUS_SEARCHING));
  send_track(track(10));
  for (int64_t s = 11; s <= 14; ++s) send_frame(s), send_track(track(s));
  send_frame(20);
  for (int64_t s = 21; s <= 24; ++s) send_frame(s), send_track(track(s));
  // AND a pair whose track was made on a frame of another size (rejected, not measured on the wrong image).
  user_track_t other_size = track(30);
  other_size.image_width = 640;
  send_frame(30);
  send_track(other_size);

  // THEN one HAND_OBS per matched seq, with that seq's utime, and nothing for 10 or 20.
  const std::set<int64_t> expected = {0, 1, 2, 3, 4, 11, 12, 13, 14, 21, 22, 23, 24};
  spin_until([&] { return obs.size() >= expected.size(); }, 10000);
  std::set<int64_t> got;
  for (const auto& [seq, m] : obs) got.insert(seq);
  EXPECT_EQ(got, expected);
  for (const auto& [seq, m] : obs) {
    EXPECT_EQ(m.utime, t0() + seq);
    if (seq == 4) {
      EXPECT_EQ(m.kind, hand_obs_t::KIND_NONE) << "a SEARCHING track gives NONE";
      EXPECT_EQ(m.track_status, user_track_t::STATUS_SEARCHING);
    } else {
      EXPECT_EQ(m.kind, hand_obs_t::KIND_OUT) << "seq " << seq;
      EXPECT_LT(m.vector[0], -100) << "the arm is on the image's left";
      EXPECT_FLOAT_EQ(m.shoulder_centre[0], 140);
      EXPECT_FLOAT_EQ(m.shoulder_centre[1], 132);
    }
  }
  // AND HEALTH counts the lone track, the lone frame and the size mismatch as rejected.
  ASSERT_TRUE(spin_until([&] { return last_health.rejected >= 3; }, 5000))
      << "rejected " << last_health.rejected << " last reason: " << last_health.last_reject_reason;
  EXPECT_EQ(last_health.rejected, 3);
  EXPECT_NE(last_health.last_reject_reason.find("640x400 frame, CAMERA has 400x400"), std::string::npos)
      << last_health.last_reject_reason;
  EXPECT_EQ(last_health.messages_out, static_cast<int64_t>(expected.size()));
}
