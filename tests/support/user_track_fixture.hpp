// A USER_TRACK of a user tracked from a manual start (track 1, confidence 10): the box (x, y, width, height)
// on a frame of the given size. The hands tests pair theirs with 400 x 400 frames, the flight tests steer on it.
#pragma once

#include <array>
#include <cstdint>

#include "gpilot/user_track_t.hpp"

namespace gpilot::test {

inline user_track_t manual_track(int64_t seq, int64_t utime, const std::array<float, 4>& box, int32_t image_width,
                                 int32_t image_height, int8_t status = user_track_t::STATUS_TRACKING) {
  user_track_t t{};
  t.utime = utime;
  t.seq = seq;
  t.status = status;
  for (size_t i = 0; i < box.size(); ++i) t.box[i] = box[i];
  t.confidence = 10;
  t.init_source = user_track_t::INIT_MANUAL;
  t.track_id = 1;
  t.image_width = image_width;
  t.image_height = image_height;
  return t;
}

// The hands tests' user: the box (100, 100, 80, 160) on a 400 x 400 frame.
inline user_track_t user_track_400(int64_t seq, int64_t utime, int8_t status = user_track_t::STATUS_TRACKING) {
  return manual_track(seq, utime, {100, 100, 80, 160}, 400, 400, status);
}

}  // namespace gpilot::test
