// A hand-made person for the keypoint-truth and scoring tests (image pixels, y down; the person faces the camera,
// so their left shoulder is on the image's right).
#pragma once

#include "keypoint_truth.hpp"

namespace gpilot::test_people {

// Shoulders L (120,100) R (80,100), hips L (115,180) R (85,180): torso centre (100,140), torso height 80,
// torso span 80..120 +- 8. Face points around (100,67): face box x 88.5..111.5, y 55.2..85.1 (grown: 83.9..116.1,
// 49.2..91.1). Arms hang straight down unless a test moves them.
inline BodyKeypoints upright() {
  BodyKeypoints k;
  auto set = [](BodyPoint& p, float x, float y) { p = BodyPoint{{x, y}, 2}; };
  set(k.nose, 100, 70);
  set(k.left_eye, 105, 65);
  set(k.right_eye, 95, 65);
  set(k.left_ear, 110, 68);
  set(k.right_ear, 90, 68);
  set(k.left_shoulder, 120, 100);
  set(k.right_shoulder, 80, 100);
  set(k.left_hip, 115, 180);
  set(k.right_hip, 85, 180);
  set(k.left_elbow, 132, 140);
  set(k.left_wrist, 138, 178);
  set(k.right_elbow, 68, 140);
  set(k.right_wrist, 62, 178);
  return k;
}

inline void arm(BodyPoint& elbow, BodyPoint& wrist, cv::Point2f e, cv::Point2f w) {
  elbow = BodyPoint{e, 2};
  wrist = BodyPoint{w, 2};
}

}  // namespace gpilot::test_people
