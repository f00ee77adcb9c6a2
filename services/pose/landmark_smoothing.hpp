// Landmark smoothing over frames as pose_landmark_filtering.pbtxt: every coordinate (x, y, z) of the 33
// landmarks and of the 2 auxiliary points through its own One Euro filter, the speed measured in object sizes
// (the mean of the points' bounding box width and height, in pixels), and visibility through a
// low-pass (presence is not smoothed). Driven by the frame's utime; reset() when the pose is lost.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "one_euro_filter.hpp"
#include "pose_landmarks.hpp"
#include "pose_params.hpp"

namespace gpilot {

class LandmarkSmoothing {
 public:
  explicit LandmarkSmoothing(const PoseSmoothingParams& params);

  // Smooths in place (nothing when params.enabled is false).
  void apply(PoseLandmarks& landmarks, std::array<cv::Point2f, 2>& aux, int64_t utime);
  void reset();

 private:
  PoseSmoothingParams params_;
  std::vector<OneEuroFilter> landmark_filters_;  // 33 x (x, y, z)
  std::vector<OneEuroFilter> aux_filters_;       // 2 x (x, y)
  std::array<float, kPoseLandmarkCount> visibility_{};  // the last smoothed visibilities
  bool visibility_started_ = false;
};

}  // namespace gpilot
