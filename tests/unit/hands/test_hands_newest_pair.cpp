// The hands stage on a bus that delivers faster than it observes (in-process, memq://): the pairs that complete
// while the loop is still dispatching are not observed one after another; the newest is, and each one it
// replaced is counted in HEALTH.dropped. A pair that completes alone is observed, as before.
#include <gtest/gtest.h>

#include <vector>

#include <opencv2/imgproc.hpp>

#include "bus_node.hpp"
#include "config.hpp"
#include "hands/hands_service.hpp"
#include "image_codec.hpp"
#include "user_track_fixture.hpp"

using namespace gpilot;

TEST(HandsNewestPair, PairsThatArriveTogetherGiveTheNewestAndCountTheRest) {
  BusNode node("gpilot-hands", "memq://");
  const auto stage = start_hands_service(Config::from_string("hands:\n  method: skin\n"), node);
  std::vector<int64_t> observed;
  node.subscribe<hand_obs_t>("HAND_OBS", [&](const hand_obs_t& m, int64_t) { observed.push_back(m.seq); });
  image_t frame = mat_to_image(cv::Mat(400, 400, CV_8UC3, cv::Scalar(200, 60, 20)), 0, 0);
  auto send_pair = [&](int64_t seq) {
    frame.seq = seq;
    frame.utime = 1000 + seq;
    node.publish("CAMERA", frame);
    node.publish("USER_TRACK", test::user_track_400(seq, 1000 + seq));
  };

  // GIVEN three pairs on the bus before the stage's loop turns (it was busy observing)
  for (int64_t seq = 1; seq <= 3; ++seq) send_pair(seq);
  node.drain();
  // THEN only the newest is observed, and the two it replaced are counted as skipped
  EXPECT_EQ(observed, std::vector<int64_t>({3}));
  EXPECT_EQ(node.stats().dropped_count(), 2);
  EXPECT_EQ(node.stats().rejected_count(), 0);

  // WHEN pairs come one at a time (the stage keeps up), each is observed and nothing more is skipped
  send_pair(4);
  node.drain();
  send_pair(5);
  node.drain();
  EXPECT_EQ(observed, std::vector<int64_t>({3, 4, 5}));
  EXPECT_EQ(node.stats().dropped_count(), 2);
}
