// TensorsToLandmarksCalculator (39 landmarks, 256 x 256, sigmoid visibility and presence) and
// LandmarkProjectionCalculator (crop -> frame through the ROI) of the pose landmark graphs.
#include "landmark_model.hpp"

#include <cmath>

#include <opencv2/dnn.hpp>

namespace gpilot {
namespace {

float sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

constexpr int kAuxCentre = 33;  //!< auxiliary points 33 and 34: the next ROI's alignment centre and scale point

}  // namespace

LandmarkOutput decode_pose_landmarks(const float* values, float pose_flag, const PoseRoi& roi) {
  LandmarkOutput out;
  if (!std::isfinite(pose_flag)) return out;
  for (int i = 0; i < kPoseLandmarkCount + 2; ++i)
    for (int k = 0; k < kLandmarkValues; ++k)
      if (!std::isfinite(values[i * kLandmarkValues + k])) return out;
  const cv::Matx23d to_image = crop_to_image(roi, kLandmarkInputSize);
  const float z_scale = roi.size / static_cast<float>(kLandmarkInputSize);
  for (int i = 0; i < kPoseLandmarkCount; ++i) {
    const float* v = values + i * kLandmarkValues;
    const cv::Point2f p = apply_affine(to_image, cv::Point2f(v[0], v[1]));
    out.landmarks[static_cast<size_t>(i)] = {p.x, p.y, v[2] * z_scale, sigmoid(v[3]), sigmoid(v[4])};
  }
  for (int i = 0; i < 2; ++i) {
    const float* v = values + (kAuxCentre + i) * kLandmarkValues;
    out.aux[static_cast<size_t>(i)] = apply_affine(to_image, cv::Point2f(v[0], v[1]));
  }
  out.pose_flag = pose_flag;
  out.finite = true;
  return out;
}

LandmarkModel::LandmarkModel(PoseNet net) : net_(std::move(net)) {}

LandmarkOutput LandmarkModel::run(const cv::Mat& bgr, const PoseRoi& roi) {
  const cv::Mat crop = warp_roi(bgr, roi, kLandmarkInputSize);
  net_.net.setInput(cv::dnn::blobFromImage(crop, 1.0 / 255.0, cv::Size(), cv::Scalar(), true, false, CV_32F));
  std::vector<cv::Mat> outs;
  net_.net.forward(outs, net_.outputs);
  return decode_pose_landmarks(outs[0].ptr<float>(), outs[1].ptr<float>()[0], roi);
}

}  // namespace gpilot
