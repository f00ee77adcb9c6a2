// Tracking as pose_landmark_cpu.pbtxt: ROI from the previous frame's auxiliary points, else from a detection.
#include "pose_estimator.hpp"

#include <cmath>
#include <stdexcept>

#include <opencv2/core/utility.hpp>

#include "box_iou.hpp"

namespace gpilot {
namespace {

// A ROI smaller than this (pixels) holds no person the model can read (its 256 px crop would magnify a few
// pixels): treated as a lost track. The detector's smallest anchors are ~30 px on the 224 input.
constexpr float kMinRoiSide = 8.0f;

bool finite_box(const cv::Rect2f& r) {
  return std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.width) && std::isfinite(r.height);
}

}  // namespace

cv::Rect2f grow_box(const cv::Rect2f& r, float share) {
  return {r.x - share * r.width, r.y - share * r.height, r.width * (1 + 2 * share), r.height * (1 + 2 * share)};
}

std::optional<PersonDetection> choose_user_detection(const std::vector<PersonDetection>& detections,
                                                     const cv::Rect2f& user_box) {
  if (detections.empty()) return std::nullopt;
  if (user_box.area() <= 0) return detections.front();
  const cv::Rect2f& gate = user_box;
  std::optional<PersonDetection> best;
  float best_iou = -1.0f;
  for (const PersonDetection& d : detections) {
    const cv::Point2f hips = d.keypoints[person_keypoint::kHipCentre];
    if (!gate.contains(hips)) continue;
    const cv::Point2f v = d.keypoints[person_keypoint::kBodyScale] - hips;
    const float half = std::sqrt(v.x * v.x + v.y * v.y);
    const float overlap = static_cast<float>(iou(cv::Rect2d(hips.x - half, hips.y - half, 2 * half, 2 * half), cv::Rect2d(user_box)));
    if (overlap > best_iou) best_iou = overlap, best = d;
  }
  return best;
}

PoseEstimator::PoseEstimator(const PoseParams& params, PoseModels models)
    : params_(params),
      detector_(params, std::move(models.detector)),
      landmark_(std::move(models.landmark)),
      smoothing_(params.smoothing) {
  cv::setNumThreads(params.threads);
}

void PoseEstimator::reset() {
  next_roi_.reset();
  smoothing_.reset();
}

PoseResult PoseEstimator::lost(PoseResult r) {
  reset();
  r.found = false;
  r.landmarks = PoseLandmarks{};
  r.counters = counters_;
  return r;
}

std::optional<PoseRoi> PoseEstimator::seed_roi(const cv::Mat& bgr, const cv::Rect2f& user_box, bool& nonfinite) {
  ++counters_.detector_runs;
  // The region grows by seed_margin of the box height on every side (a share of the width would hardly widen a
  // tall thin box, and the detector needs the person's surroundings: arms stretched out, the head).
  const float grow = static_cast<float>(params_.seed_margin) * user_box.height;
  const cv::Rect2f region = user_box.area() > 0
                                ? cv::Rect2f(user_box.x - grow, user_box.y - grow, user_box.width + 2 * grow,
                                             user_box.height + 2 * grow)
                                : cv::Rect2f();
  const std::vector<PersonDetection> found = detector_.detect(bgr, region);
  if (detector_.last_nonfinite() > 0) {
    nonfinite = true;
    return std::nullopt;
  }
  const std::optional<PersonDetection> d = choose_user_detection(found, user_box);
  if (!d) return std::nullopt;
  return roi_from_alignment(d->keypoints[person_keypoint::kHipCentre], d->keypoints[person_keypoint::kBodyScale],
                            static_cast<float>(params_.roi_scale));
}

PoseResult PoseEstimator::estimate(const cv::Mat& bgr, const cv::Rect2f& user_box, int64_t utime) {
  if (bgr.empty() || bgr.type() != CV_8UC3)
    throw std::invalid_argument("PoseEstimator::estimate: the frame must be a non-empty CV_8UC3 image");
  if (!finite_box(user_box)) throw std::invalid_argument("PoseEstimator::estimate: the user box is not finite");
  PoseResult r;
  std::optional<PoseRoi> roi = next_roi_;
  // A track whose hips left the user's box may have slid onto someone else: the detector decides again.
  if (roi && user_box.area() > 0 && !grow_box(user_box, static_cast<float>(params_.track_margin)).contains(roi->centre)) {
    reset();
    roi.reset();
  }
  if (roi) {
    ++counters_.frames_tracked;
  } else {
    bool nonfinite = false;
    r.detector_ran = true;
    roi = seed_roi(bgr, user_box, nonfinite);
    if (nonfinite) ++counters_.nonfinite_outputs;
    if (!roi) return lost(r);
  }
  if (!(roi->size >= kMinRoiSide)) return lost(r);
  r.roi = *roi;
  LandmarkOutput out = landmark_.run(bgr, *roi);
  if (!out.finite) {
    ++counters_.nonfinite_outputs;
    return lost(r);
  }
  r.pose_flag = out.pose_flag;
  if (out.pose_flag < params_.pose_flag_threshold) return lost(r);
  smoothing_.apply(out.landmarks, out.aux, utime);
  next_roi_ = roi_from_alignment(out.aux[0], out.aux[1], static_cast<float>(params_.roi_scale));
  r.found = true;
  r.landmarks = out.landmarks;
  r.counters = counters_;
  return r;
}

}  // namespace gpilot
