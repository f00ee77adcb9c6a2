// MediaPipe's alignment-points ROI and its crop (ImageToTensorCalculator's rotated sub-rectangle).
#include "pose_roi.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace gpilot {
float normalize_radians(float a) {
  const double two_pi = 2.0 * CV_PI;
  return static_cast<float>(a - two_pi * std::floor((a + CV_PI) / two_pi));
}

PoseRoi roi_from_alignment(const cv::Point2f& centre, const cv::Point2f& scale_point, float scale) {
  const cv::Point2f d = scale_point - centre;
  PoseRoi roi;
  roi.centre = centre;
  // A square already: square_long leaves the side as it is.
  roi.size = 2.0f * std::sqrt(d.x * d.x + d.y * d.y) * scale;
  // The y axis points down, so the vector's angle is taken with y flipped (DetectionsToRectsCalculator).
  roi.rotation = normalize_radians(kPoseRoiTargetAngle - std::atan2(-d.y, d.x));
  return roi;
}

cv::Matx23d crop_to_image(const PoseRoi& roi, int crop_size) {
  const double k = static_cast<double>(roi.size) / crop_size;
  const double c = std::cos(static_cast<double>(roi.rotation)) * k, s = std::sin(static_cast<double>(roi.rotation)) * k;
  const double half = crop_size / 2.0;
  return {c, -s, roi.centre.x - (c * half - s * half), s, c, roi.centre.y - (s * half + c * half)};
}

cv::Matx23d image_to_crop(const PoseRoi& roi, int crop_size) {
  cv::Matx23d inverse;
  cv::invertAffineTransform(crop_to_image(roi, crop_size), inverse);
  return inverse;
}

cv::Mat warp_roi(const cv::Mat& image, const PoseRoi& roi, int crop_size) {
  // cv::warpAffine addresses pixels by their centres (pixel i at i): shift by half a pixel on both sides.
  cv::Matx23d m = image_to_crop(roi, crop_size);
  for (int r = 0; r < 2; ++r) m(r, 2) += 0.5 * (m(r, 0) + m(r, 1)) - 0.5;
  cv::Mat crop;
  cv::warpAffine(image, crop, m, cv::Size(crop_size, crop_size), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return crop;
}

cv::Point2f apply_affine(const cv::Matx23d& m, const cv::Point2f& p) {
  return {static_cast<float>(m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2)),
          static_cast<float>(m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2))};
}

}  // namespace gpilot
