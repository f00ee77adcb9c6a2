// The rotated square region the landmark model sees, as MediaPipe's AlignmentPointsRectsCalculator and
// RectTransformationCalculator make it (pose_detection_to_roi.pbtxt, pose_landmarks_to_roi.pbtxt): centred
// on an alignment centre (the hips' midpoint), side 2 x |scale point - centre| x scale, turned so that the
// scale point (above the head for an upright person) is straight up in the crop.
//
// Coordinates: image pixels with pixel i spanning [i, i+1] (its centre at i + 0.5); the crop likewise, N x N.
// A crop point (a, b) is the image point centre + R(rotation) (S/N) (a - N/2, b - N/2), R the rotation
// [cos -sin; sin cos] in image axes (y down): a positive rotation turns the crop's up towards the image's right.
#pragma once

#include <opencv2/core.hpp>

namespace gpilot {

struct PoseRoi {
  cv::Point2f centre;  //!< image pixels
  float size = 0;      //!< side, image pixels
  float rotation = 0;  //!< radians in [-pi, pi): the crop's up is R(rotation) (0, -1) in the image
};

// MediaPipe's rotation_vector_target_angle_degrees: the centre-to-scale-point vector points up in the crop.
constexpr float kPoseRoiTargetAngle = static_cast<float>(CV_PI / 2.0);

// NormalizeRadians of MediaPipe's calculators: a into [-pi, pi).
float normalize_radians(float a);

// The ROI from an alignment centre and scale point (a detection's keypoints 0 and 1, or the previous frame's
// auxiliary landmarks 33 and 34), grown by scale (PoseParams::roi_scale).
PoseRoi roi_from_alignment(const cv::Point2f& centre, const cv::Point2f& scale_point, float scale);

// The affine map of crop points (N x N crop, continuous coordinates as above) to image points, and its inverse.
cv::Matx23d crop_to_image(const PoseRoi& roi, int crop_size);
cv::Matx23d image_to_crop(const PoseRoi& roi, int crop_size);

// The N x N crop of image (any type cv::warpAffine takes), bilinear; outside the image the nearest edge pixel
// (MediaPipe's ImageToTensorCalculator default border, BORDER_REPLICATE).
cv::Mat warp_roi(const cv::Mat& image, const PoseRoi& roi, int crop_size);

cv::Point2f apply_affine(const cv::Matx23d& m, const cv::Point2f& p);

}  // namespace gpilot
