// BlazePose's two nets on cv::dnn (OpenCV backend, CPU): the person detector (RGB in [-1, 1], 224 x 224 ->
// 2254 x 12 box/keypoint regressions and 2254 score logits) and a landmark model (RGB in [0, 1], 256 x 256 ->
// 39 x 5 landmark values and the pose flag). Loaded and checked once, at start: a missing, truncated or
// wrong-shaped file throws PoseModelError naming it, so the adapter stops before the bus starts.
#pragma once

#include <stdexcept>
#include <string>

#include <opencv2/dnn.hpp>

#include "pose_params.hpp"

namespace gpilot {

class PoseModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The nets' fixed shapes (MediaPipe's pose_detection and pose_landmark graphs).
constexpr int kDetectorInputSize = 224;
constexpr int kDetectorAnchors = 2254;
constexpr int kDetectorBoxValues = 12;    //!< box cx, cy, w, h + 4 keypoints x, y
constexpr int kLandmarkInputSize = 256;
constexpr int kLandmarkPoints = 39;       //!< 33 landmarks + 6 auxiliary (the first two make the next ROI)
constexpr int kLandmarkValues = 5;        //!< x, y, z, visibility logit, presence logit

// One loaded net and the names of its outputs in the order the core reads them.
struct PoseNet {
  cv::dnn::Net net;
  std::vector<std::string> outputs;  //!< detector: boxes, scores; landmark: landmarks, pose flag
  std::string path;
};

struct PoseModels {
  PoseNet detector;
  PoseNet landmark;

  // models_dir/pose_detection.onnx and models_dir/pose_landmark_<model>.onnx, models_dir through
  // resolve_project_path.
  static PoseModels load(const PoseParams& params);
  // Explicit files; fast_depthwise as PoseParams::fast_depthwise.
  static PoseModels load(const std::string& detector_path, const std::string& landmark_path, bool fast_depthwise = true);
  // The person detector alone (the tracker's person search), checked as load() checks it.
  static PoseNet load_detector(const std::string& detector_path, bool fast_depthwise = true);
};

// The files load(params) reads.
std::string pose_detector_path(const PoseParams& params);
std::string pose_landmark_path(const PoseParams& params);

}  // namespace gpilot
