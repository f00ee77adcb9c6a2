// One person found by BlazePose's detector: a face box and four alignment keypoints (pose_detection_cpu.pbtxt):
// 0 the hips' midpoint, 1 a point that sets the full body's size and rotation, 2 the shoulders' midpoint, 3 the
// same for the upper body. Coordinates are those of the image the caller gave (pixels, pixel i spans [i, i+1]).
#pragma once

#include <array>

#include <opencv2/core.hpp>

namespace gpilot {

struct PersonDetection {
  float score = 0;                          //!< 0..1 (sigmoid of the clipped logit)
  cv::Rect2f face;                          //!< the face box
  std::array<cv::Point2f, 4> keypoints{};   //!< hip centre, full-body scale point, shoulder centre, upper-body scale point
};

namespace person_keypoint {
enum Index : int { kHipCentre = 0, kBodyScale = 1, kShoulderCentre = 2, kUpperBodyScale = 3 };
}  // namespace person_keypoint

}  // namespace gpilot
