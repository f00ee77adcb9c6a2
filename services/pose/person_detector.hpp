// BlazePose's person detector (pose_detection_cpu.pbtxt): a region of the frame letterboxed to 224 x 224 (aspect
// kept, black bars), the net, the 2254 anchors' regressions decoded, scores through a clipped sigmoid, weighted
// NMS, and the detections back in frame pixels.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "person_detection.hpp"
#include "pose_models.hpp"
#include "pose_params.hpp"

namespace gpilot {

// Decodes the net's raw outputs (boxes: 2254 x 12, scores: 2254 logits; input pixels of the 224 x 224 tensor,
// relative to the anchors) into detections in tensor pixels, those scoring at least score_threshold. A row
// with a non-finite value is skipped and counted in *nonfinite (when given).
std::vector<PersonDetection> decode_person_detections(const float* boxes, const float* scores, const PoseParams& params,
                                                      int* nonfinite = nullptr);

class PersonDetector {
 public:
  PersonDetector(const PoseParams& params, PoseNet net);

  // Detections in bgr's pixels, best first. region: the part of the frame looked at (pixels; it may reach out of
  // the frame, which is seen black); empty = the whole frame. bgr: CV_8UC3, not empty.
  std::vector<PersonDetection> detect(const cv::Mat& bgr, const cv::Rect2f& region = {});

  // Rows of the last detect() with NaN/Inf in the net's output (skipped).
  int last_nonfinite() const { return last_nonfinite_; }

 private:
  PoseParams params_;
  PoseNet net_;
  int last_nonfinite_ = 0;
};

}  // namespace gpilot
