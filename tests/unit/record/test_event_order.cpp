// gpilot-record writes events of two sockets in arrival order: known answers.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "event_order.hpp"

namespace gpilot {
namespace {

std::vector<std::string> release(EventOrder& order, int64_t before) {
  std::vector<std::string> out;
  order.release_before(before, [&](const EventOrder::Event& e) {
    out.push_back(e.channel + "@" + std::to_string(e.utime) + ":" + std::string(e.data.begin(), e.data.end()));
  });
  return out;
}

// GIVEN a track dispatched before a frame that arrived 1 ms earlier (the frames' socket polled second),
// and two events of the same instant
TEST(EventOrder, EventsAreWrittenInArrivalOrderOnceOldEnough) {
  EventOrder order;
  order.add(2000, "USER_TRACK", "t", 1);
  order.add(1000, "CAMERA", "f", 1);
  order.add(3000, "HEALTH", "a", 1);
  order.add(3000, "CONFIG", "b", 1);
  // WHEN those received before 2500 are released THEN the frame comes first, later ones are held
  EXPECT_EQ(release(order, 2500), (std::vector<std::string>{"CAMERA@1000:f", "USER_TRACK@2000:t"}));
  EXPECT_EQ(order.held(), 2u);
  // AND at the end, the rest, equal times in the order they were dispatched
  EXPECT_EQ(release(order, INT64_MAX), (std::vector<std::string>{"HEALTH@3000:a", "CONFIG@3000:b"}));
  EXPECT_EQ(order.held(), 0u);
}

}  // namespace
}  // namespace gpilot
