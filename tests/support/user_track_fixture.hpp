// The USER_TRACK the hands tests pair with their 400 x 400 frames: the user's box at (100, 100, 80, 160),
// tracked from a manual start.
#pragma once

#include <cstdint>

#include "gpilot/user_track_t.hpp"

namespace gpilot::test {

inline user_track_t user_track_400(int64_t seq, int64_t utime, int8_t status = user_track_t::STATUS_TRACKING) {
  user_track_t t{};
  t.utime = utime;
  t.seq = seq;
  t.status = status;
  t.box[0] = 100;
  t.box[1] = 100;
  t.box[2] = 80;
  t.box[3] = 160;
  t.confidence = 10;
  t.init_source = user_track_t::INIT_MANUAL;
  t.track_id = 1;
  t.image_width = 400;
  t.image_height = 400;
  return t;
}

}  // namespace gpilot::test
