// The user search of the paper: OpenCV's Haar face cascade (file from opencv-data, a config key) on the
// frame or a shrunk copy, and the body box made from the face box by the head-body ratio.
#pragma once

#include <optional>

#include <opencv2/core.hpp>
#include <opencv2/objdetect.hpp>

#include "tracker_params.hpp"

namespace gpilot {

struct FaceDetection {
  cv::Rect2d face;  //!< pixels, in the frame given
  cv::Rect2d body;  //!< body box from the head-body ratio, clipped to the frame
};

// The body box of a face box (not clipped): centred on the face horizontally, its top a little above the
// face top, its size the head-body ratios of params.
cv::Rect2d body_from_face(const cv::Rect2d& face, const TrackerParams& params);

// Where the face re-check looks for the face of a body box: 3 face widths wide centred on the box, from 0.75
// face heights above the face top the head-body ratios put there, 2.5 face heights tall (not clipped).
cv::Rect face_recheck_window(const cv::Rect2d& body, const TrackerParams& params);

class FaceDetector {
 public:
  // Throws std::runtime_error when the cascade file is missing or does not load.
  explicit FaceDetector(const TrackerParams& params);

  // The largest face in frame (CV_8UC3 or CV_8UC1), or none.
  std::optional<FaceDetection> detect(const cv::Mat& frame);
  // The same, searching only the part of roi inside frame; boxes in frame pixels.
  std::optional<FaceDetection> detect(const cv::Mat& frame, const cv::Rect& roi);

 private:
  TrackerParams p_;
  cv::CascadeClassifier cascade_;
  cv::Mat grey_, small_;
};

}  // namespace gpilot
