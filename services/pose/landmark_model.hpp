// BlazePose's landmark model on one ROI (pose_landmark_by_roi_cpu.pbtxt, tensors_to_pose_landmarks_and_
// segmentation.pbtxt): the ROI warped to 256 x 256 RGB in [0, 1], the net, and its 39 x 5 values back in frame
// pixels: 33 landmarks (visibility and presence through a sigmoid, z scaled like x: crop pixels times the ROI's
// size / 256, as MediaPipe's projection) and the first two auxiliary points, which make the next frame's ROI.
#pragma once

#include <array>

#include <opencv2/core.hpp>

#include "pose_landmarks.hpp"
#include "pose_models.hpp"
#include "pose_roi.hpp"

namespace gpilot {

struct LandmarkOutput {
  bool finite = false;                 //!< false: the net gave NaN/Inf; nothing else is set
  float pose_flag = 0;                 //!< probability that a pose is in the ROI
  PoseLandmarks landmarks{};           //!< frame pixels
  std::array<cv::Point2f, 2> aux{};    //!< auxiliary points 33 (centre) and 34 (scale point), frame pixels
};

// Decodes the net's raw outputs (39 x 5 values in crop pixels, the pose flag) for a crop of roi.
LandmarkOutput decode_pose_landmarks(const float* values, float pose_flag, const PoseRoi& roi);

class LandmarkModel {
 public:
  explicit LandmarkModel(PoseNet net);

  // The landmarks of the person in roi of bgr (CV_8UC3, not empty).
  LandmarkOutput run(const cv::Mat& bgr, const PoseRoi& roi);

 private:
  PoseNet net_;
};

}  // namespace gpilot
