// A run's LCM log made up for the tests of gpilot-view and gpilot-report, with every value known:
// CAMERA frames drawn with cv:: primitives, and USER_TRACK, HAND_OBS, GESTURE_CMD, FLIGHT_SETPOINT,
// VEHICLE_STATE, GROUND_TRUTH and HEALTH events at chosen receipt times (written with lcm::LogFile "w",
// the same format lcm-logger writes).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"

namespace gpilot::test {

struct SyntheticRun {
  int frames = 100;
  cv::Size size{320, 240};
  int64_t t0 = 1700000000000000;    // frame 0's utime
  int64_t frame_period_us = 40000;  // 25 fps
  int8_t pixel_format = image_t::PIXEL_FORMAT_BGR8;
  // GROUND_TRUTH.expected_mode and GESTURE_CMD.mode of frame seq.
  std::function<int8_t(int64_t)> expected_mode = [](int64_t s) {
    return s < 50 ? gesture_cmd_t::MODE_FINE : gesture_cmd_t::MODE_CLOSER;
  };
  std::function<int8_t(int64_t)> decided_mode = default_decided;
  // USER_TRACK.facing of frame seq.
  std::function<int8_t(int64_t)> facing = [](int64_t) { return user_track_t::FACING_TOWARD; };
  // Receipt time of the frame's GESTURE_CMD minus its utime; FLIGHT_SETPOINT follows 5 ms later.
  std::function<int64_t(int64_t)> cmd_latency_us = [](int64_t s) { return 70000 + (s % 10) * 1000; };
  bool with_truth = true;
  bool with_hand = true;
  bool with_health = true;

  // Decided modes of the default run: the buffer's lag after each change, and two errors (seq 40, 90).
  static int8_t default_decided(int64_t s);
};

// Known geometry of frame seq (pixels): the user box moves 4 px a frame so a mark drawn on the wrong frame
// is found out.
cv::Rect2f user_box_of(int64_t seq);
cv::Point2f shoulder_centre_of(int64_t seq);  // p_uc
cv::Point2f body_centre_of(int64_t seq);      // p_bc
cv::Rect2f hand_box_of(int64_t seq);
constexpr float kFineDirection[2] = {0.6f, -0.1f};  // GESTURE_CMD.direction of FINE frames

// The frame itself: grey background, a blue "person" in the user box, the seq as text.
cv::Mat frame_of(int64_t seq, const cv::Size& size);

// The per-frame and state messages of frame seq.
image_t camera_of(const SyntheticRun& run, int64_t seq);
user_track_t track_of(const SyntheticRun& run, int64_t seq);
hand_obs_t hand_of(const SyntheticRun& run, int64_t seq);
gesture_cmd_t cmd_of(const SyntheticRun& run, int64_t seq);
ground_truth_t truth_of(const SyntheticRun& run, int64_t seq);
vehicle_state_t vehicle_of(const SyntheticRun& run, int64_t seq);

// HEALTH report i of a stage: rate_out 0 on report 0, then 24, 25, 26, 24, ...; p50 2+i ms, p99 10+i ms.
health_t health_of(const std::string& name, int64_t i, int64_t utime);

// Writes the run to path, events in receipt-time order. Returns the number of events written.
int64_t write_synthetic_log(const std::string& path, const SyntheticRun& run);

}  // namespace gpilot::test
