// TensorsToDetectionsCalculator (reverse_output_order, scales 224), NonMaxSuppressionCalculator and
// DetectionLetterboxRemovalCalculator with pose_detection_cpu.pbtxt's options.
#include "person_detector.hpp"

#include <cmath>

#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "pose_roi.hpp"
#include "ssd_anchors.hpp"
#include "weighted_nms.hpp"

namespace gpilot {

std::vector<PersonDetection> decode_person_detections(const float* boxes, const float* scores, const PoseParams& params,
                                                      int* nonfinite) {
  const std::vector<SsdAnchor>& anchors = pose_detector_anchors();
  const float size = static_cast<float>(kDetectorInputSize);
  const float clip = static_cast<float>(params.score_clipping);
  std::vector<PersonDetection> out;
  for (size_t i = 0; i < anchors.size(); ++i) {
    const float* r = boxes + i * kDetectorBoxValues;
    bool finite = std::isfinite(scores[i]);
    for (int k = 0; k < kDetectorBoxValues; ++k) finite = finite && std::isfinite(r[k]);
    if (!finite) {
      if (nonfinite) ++*nonfinite;
      continue;
    }
    const float score = 1.0f / (1.0f + std::exp(-std::clamp(scores[i], -clip, clip)));
    if (score < params.detector_score_threshold) continue;
    const SsdAnchor& a = anchors[i];
    // Offsets in input pixels from the anchor centre; sizes in input pixels (fixed anchors of size 1).
    const float cx = (r[0] / size * a.width + a.x_center) * size, cy = (r[1] / size * a.height + a.y_center) * size;
    const float w = r[2] / size * a.width * size, h = r[3] / size * a.height * size;
    PersonDetection d;
    d.score = score;
    d.face = cv::Rect2f(cx - w / 2, cy - h / 2, w, h);
    for (size_t k = 0; k < d.keypoints.size(); ++k)
      d.keypoints[k] = cv::Point2f((r[4 + 2 * k] / size * a.width + a.x_center) * size,
                                   (r[5 + 2 * k] / size * a.height + a.y_center) * size);
    out.push_back(d);
  }
  return out;
}

PersonDetector::PersonDetector(const PoseParams& params, PoseNet net) : params_(params), net_(std::move(net)) {}

std::vector<PersonDetection> PersonDetector::detect(const cv::Mat& bgr, const cv::Rect2f& region_in) {
  const cv::Rect2f region = region_in.area() > 0 ? region_in : cv::Rect2f(0, 0, static_cast<float>(bgr.cols), static_cast<float>(bgr.rows));
  // Letterbox: the region's long side fills the tensor, centred, the rest black (ImageToTensorCalculator,
  // keep_aspect_ratio, BORDER_ZERO). An unrotated square ROI around the region's centre does exactly that.
  PoseRoi box;
  box.centre = cv::Point2f(region.x + region.width / 2, region.y + region.height / 2);
  box.size = std::max(region.width, region.height);
  cv::Mat crop;
  {
    cv::Matx23d m = image_to_crop(box, kDetectorInputSize);
    for (int r = 0; r < 2; ++r) m(r, 2) += 0.5 * (m(r, 0) + m(r, 1)) - 0.5;  // pixel centres, as warp_roi
    // Outside the region is black too: only the region is looked at.
    const cv::Rect inside = cv::Rect(cv::Point(static_cast<int>(std::floor(region.x)), static_cast<int>(std::floor(region.y))),
                                     cv::Point(static_cast<int>(std::ceil(region.x + region.width)),
                                               static_cast<int>(std::ceil(region.y + region.height)))) &
                            cv::Rect(0, 0, bgr.cols, bgr.rows);
    // A new buffer, never bgr's: the caller's frame is not touched.
    cv::Mat masked;
    if (inside == cv::Rect(0, 0, bgr.cols, bgr.rows)) {
      masked = bgr;
    } else {
      masked.create(bgr.size(), bgr.type());
      masked.setTo(cv::Scalar::all(0));
      bgr(inside).copyTo(masked(inside));
    }
    cv::warpAffine(masked, crop, m, cv::Size(kDetectorInputSize, kDetectorInputSize), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  }
  // RGB in [-1, 1].
  const cv::Mat blob = cv::dnn::blobFromImage(crop, 2.0 / 255.0, cv::Size(), cv::Scalar(127.5, 127.5, 127.5), true, false, CV_32F);
  net_.net.setInput(blob);
  std::vector<cv::Mat> outs;
  net_.net.forward(outs, net_.outputs);
  last_nonfinite_ = 0;
  std::vector<PersonDetection> found =
      decode_person_detections(outs[0].ptr<float>(), outs[1].ptr<float>(), params_, &last_nonfinite_);
  found = weighted_nms(std::move(found), static_cast<float>(params_.nms_iou_threshold));
  const cv::Matx23d back = crop_to_image(box, kDetectorInputSize);
  for (PersonDetection& d : found) {
    const cv::Point2f tl = apply_affine(back, d.face.tl()), br = apply_affine(back, d.face.br());
    d.face = cv::Rect2f(tl, br);
    for (cv::Point2f& k : d.keypoints) k = apply_affine(back, k);
  }
  return found;
}

}  // namespace gpilot
