// Real LCM traffic (inside the private network namespace that tests/netns-run makes): a 1280x720 BGR
// frame arrives byte-identical, and malformed or invalid messages are counted with a reason in HEALTH
// while the receiving node keeps running.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>

#include "bus_node.hpp"
#include "image_codec.hpp"

namespace gpilot {
namespace {

const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

bool rmem_allows_720p() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  int64_t v = 0;
  in >> v;
  return v >= 4194304;
}

// Spins node until pred() holds or 3 s pass.
template <class Pred>
bool spin_until(BusNode& node, Pred pred) {
  const int64_t end = monotonic_utime() + 3'000'000;
  while (!pred() && monotonic_utime() < end) node.spin_once(20);
  return pred();
}

TEST(BusLcm, FullHdFrameArrivesByteIdentical) {
  if (!rmem_allows_720p()) GTEST_SKIP() << "net.core.rmem_max < 4 MiB: 1280x720 frames cannot be received here";
  BusNode rx("rx", kUrl), tx("tx", kUrl);
  std::optional<image_t> got;
  rx.subscribe<image_t>("CAMERA", [&](const image_t& m, int64_t) { got = m; });

  cv::Mat frame(720, 1280, CV_8UC3);
  cv::randu(frame, 0, 256);
  const int64_t now = wall_utime();
  const image_t sent = mat_to_image(frame, now, 77);
  ASSERT_EQ(sent.size, 1280 * 720 * 3);
  tx.publish("CAMERA", sent);
  ASSERT_TRUE(spin_until(rx, [&] { return got.has_value(); })) << "no frame within 3 s";
  EXPECT_EQ(got->seq, 77);
  EXPECT_EQ(got->utime, now);
  EXPECT_EQ(got->data, sent.data);
  cv::Mat back;
  ASSERT_EQ(image_to_mat(*got, back), "");
  EXPECT_EQ(cv::norm(frame, back, cv::NORM_INF), 0.0);
  EXPECT_EQ(rx.stats().accepted_count(), 1);
  EXPECT_EQ(rx.stats().rejected_count(), 0);
}

TEST(BusLcm, BadMessagesAreCountedAndReportedInHealth) {
  BusNode rx("gpilot-test-rx", kUrl), tx("tx", kUrl), monitor("monitor", kUrl);
  int images = 0, commands = 0;
  rx.subscribe<image_t>("CAMERA", [&](const image_t&, int64_t) { ++images; });
  rx.subscribe<gesture_cmd_t>("GESTURE_CMD", [&](const gesture_cmd_t&, int64_t) { ++commands; });
  std::optional<health_t> health;
  monitor.subscribe<health_t>("HEALTH", [&](const health_t& h, int64_t) {
    if (h.name == "gpilot-test-rx") health = h;
  });

  // GIVEN a valid frame, then the same frame truncated to half its bytes
  const image_t good = mat_to_image(cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 20, 30)), wall_utime(), 1);
  std::vector<uint8_t> bytes(good.getEncodedSize());
  good.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  tx.publish("CAMERA", good);
  tx.publish_raw("CAMERA", bytes.data(), bytes.size() / 2);
  // AND a frame whose data is too small for its width x height
  image_t wrong = good;
  wrong.height = 96;
  tx.publish("CAMERA", wrong);
  // (frames travel on a port of their own: no order between them and commands unless waited for)
  ASSERT_TRUE(spin_until(rx, [&] { return rx.stats().accepted_count() + rx.stats().rejected_count() >= 3; }));
  // AND a command with a NaN, then a valid one
  gesture_cmd_t cmd{};
  cmd.utime = wall_utime();
  cmd.direction[0] = std::numeric_limits<float>::quiet_NaN();
  tx.publish("GESTURE_CMD", cmd);
  cmd.direction[0] = 0.5f;
  cmd.seq = 1;
  tx.publish("GESTURE_CMD", cmd);

  // WHEN the receiver handles them
  ASSERT_TRUE(spin_until(rx, [&] { return rx.stats().accepted_count() + rx.stats().rejected_count() >= 5; }));
  // THEN only the valid ones reached the handlers, the rest were counted with a reason
  EXPECT_EQ(images, 1);
  EXPECT_EQ(commands, 1);
  EXPECT_EQ(rx.stats().rejected_count(), 3);
  EXPECT_EQ(rx.stats().last_reject_reason(), "GESTURE_CMD: direction is not finite");

  // AND its HEALTH says so on the bus, and it is still running
  rx.publish_health();
  ASSERT_TRUE(spin_until(monitor, [&] { return health.has_value(); }));
  EXPECT_EQ(health->rejected, 3);
  EXPECT_EQ(health->messages_in, 2);
  EXPECT_EQ(health->last_reject_reason, "GESTURE_CMD: direction is not finite");
  image_t next = good;
  next.utime = wall_utime();
  next.seq = 2;
  tx.publish("CAMERA", next);
  ASSERT_TRUE(spin_until(rx, [&] { return images == 2; }));
}

TEST(BusLcm, TruncatedImageReasonNamesTheType) {
  BusNode rx("rx", kUrl), tx("tx", kUrl);
  rx.subscribe<image_t>("CAMERA", [&](const image_t&, int64_t) {});
  const uint8_t junk[5] = {1, 2, 3, 4, 5};
  tx.publish_raw("CAMERA", junk, sizeof junk);
  ASSERT_TRUE(spin_until(rx, [&] { return rx.stats().rejected_count() == 1; }));
  EXPECT_EQ(rx.stats().last_reject_reason(),
            "CAMERA: 5 bytes do not decode as gpilot.image_t (truncated, malformed or another type)");
}

TEST(BusLcm, TimersRunFromTheLoopOnTheNodesClock) {
  // GIVEN a node whose timer clock the test moves by hand, with a 10 ms timer
  BusNode node("timer", kUrl);
  int64_t now = 1'000'000;
  node.set_timer_clock([&] { return now; });
  int ticks = 0;
  node.every(0.01, [&] { ++ticks; });
  // One loop step after the clock moved by us: the ticks so far.
  const auto after = [&](int64_t us) {
    now += us;
    node.spin_once(0);
    return ticks;
  };
  // WHEN the loop turns without the clock moving THEN nothing fires
  EXPECT_EQ(after(0), 0);
  // WHEN 200 ms pass in steps of 10 ms, one loop step each THEN the timer fired 20 times
  for (int i = 0; i < 20; ++i) after(10'000);
  EXPECT_EQ(ticks, 20);
  // AND a microsecond before its period ends it has not fired again; at the end it has
  EXPECT_EQ(after(9'999), 20);
  EXPECT_EQ(after(1), 21);
  // AND after a 100 ms stall it fires once, not ten times to catch up, and keeps its period from there
  EXPECT_EQ(after(100'000), 22);
  EXPECT_EQ(after(9'999), 22);
  EXPECT_EQ(after(1), 23);
}

TEST(BusLcm, BadUrlIsAClearError) {
  // An unusable URL: construction fails with a message instead of giving a silent node.
  try {
    BusNode node("bad", "udpm://300.1.1.1:7667?ttl=0");
    FAIL() << "expected BusError";
  } catch (const BusError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot start LCM"), std::string::npos);
  }
}

TEST(FramesUrl, DerivedFromTheBusUrlOrGiven) {
  const BusParams defaults;
  EXPECT_EQ(frames_url_for(kUrl, defaults), "udpm://239.255.76.67:7668?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(frames_url_for("udpm://239.255.76.67", defaults), "udpm://239.255.76.67:7668");
  EXPECT_EQ(frames_url_for("udpm://239.255.76.70:9000?ttl=1", defaults), "udpm://239.255.76.70:9001?ttl=1");
  EXPECT_EQ(frames_url_for("memq://", defaults), "memq://") << "one process: one bus";
  BusParams given;
  given.frames_url = "udpm://239.255.76.68:7667?ttl=0";
  EXPECT_EQ(frames_url_for(kUrl, given), "udpm://239.255.76.68:7667?ttl=0");
}

// Raw LCM on url: every channel name it receives (but LCM's own start-up self tests).
struct Listener {
  explicit Listener(const std::string& url) : lcm(url) {
    lcm.subscribeFunction(".*", +[](const lcm::ReceiveBuffer*, const std::string& ch, std::vector<std::string>* seen) {
      if (ch != "LCM_SELF_TEST") seen->push_back(ch);
    }, &seen);
  }
  void drain_for(int ms) {
    const int64_t end = monotonic_utime() + ms * 1000;
    while (monotonic_utime() < end) lcm.handleTimeout(10);
  }
  lcm::LCM lcm;
  std::vector<std::string> seen;
};

// GIVEN the default bus.frames_channels (CAMERA|GROUND_TRUTH) and a frames URL derived from the bus URL
// WHEN a node publishes a frame and a track
// THEN a subscriber of both gets both, the bus URL carries only the track and the frames URL only the frame:
// a process without a CAMERA subscription has no socket that a frame reaches
TEST(FramesUrl, FramesTravelOnTheirOwnPortAndReachOnlyTheirSubscribers) {
  BusNode tx("tx", kUrl), rx("rx", kUrl), other("decide", kUrl);
  Listener bus(kUrl), frames(frames_url_for(kUrl, BusParams{}));
  EXPECT_EQ(rx.frames_url(), "udpm://239.255.76.67:7668?ttl=0&recv_buf_size=4194304");
  EXPECT_TRUE(rx.on_frames_bus("CAMERA"));
  EXPECT_TRUE(rx.on_frames_bus("GROUND_TRUTH"));
  EXPECT_FALSE(rx.on_frames_bus("USER_TRACK"));
  EXPECT_FALSE(rx.on_frames_bus("CAMERA_2")) << "a regex matches whole names";
  int frames_in = 0, tracks_in = 0, commands_in = 0;
  rx.subscribe<image_t>("CAMERA", [&](const image_t& m, int64_t) { frames_in += m.seq == 5; });
  rx.subscribe<user_track_t>("USER_TRACK", [&](const user_track_t& m, int64_t) { tracks_in += m.seq == 5; });
  other.subscribe<gesture_cmd_t>("GESTURE_CMD", [&](const gesture_cmd_t&, int64_t) { ++commands_in; });
  const image_t frame = mat_to_image(cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 20, 30)), wall_utime(), 5);
  user_track_t track{};
  track.utime = frame.utime;
  track.seq = 5;
  tx.publish("CAMERA", frame);
  tx.publish("USER_TRACK", track);
  ASSERT_TRUE(spin_until(rx, [&] { return frames_in == 1 && tracks_in == 1; }));
  bus.drain_for(100);
  frames.drain_for(100);
  EXPECT_EQ(bus.seen, (std::vector<std::string>{"USER_TRACK"}));
  EXPECT_EQ(frames.seen, (std::vector<std::string>{"CAMERA"}));
  other.spin_once(50);
  EXPECT_EQ(other.stats().accepted_count() + other.stats().rejected_count(), 0);
}

// GIVEN bus.frames_url set to the bus URL: one bus, as before frames had a port of their own
TEST(FramesUrl, TheBusUrlAsFramesUrlIsOneBus) {
  BusParams one;
  one.frames_url = kUrl;
  BusNode tx("tx", kUrl, one);
  EXPECT_FALSE(tx.on_frames_bus("CAMERA"));
  Listener bus(kUrl);
  tx.publish("CAMERA", mat_to_image(cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3)), wall_utime(), 1));
  bus.drain_for(100);
  EXPECT_EQ(bus.seen, (std::vector<std::string>{"CAMERA"}));
}

// A raw subscription (recorders, gpilot-view) hears both URLs.
TEST(FramesUrl, ARawSubscriptionHearsBothUrls) {
  BusNode tx("tx", kUrl), rec("rec", kUrl);
  std::vector<std::string> seen;
  rec.subscribe_raw(".*", [&](const std::string& ch, const void*, size_t, int64_t) {
    if (ch != "HEALTH") seen.push_back(ch);
  });
  user_track_t track{};
  track.utime = wall_utime();
  tx.publish("CAMERA", mat_to_image(cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3)), wall_utime(), 1));
  tx.publish("USER_TRACK", track);
  ASSERT_TRUE(spin_until(rec, [&] { return seen.size() == 2; }));
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (std::vector<std::string>{"CAMERA", "USER_TRACK"}));
}

}  // namespace
}  // namespace gpilot
