// Tracking as pose_landmark_cpu.pbtxt: ROI from the previous frame's auxiliary points, else from a detection.
#include "pose_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

std::vector<PersonDetection> user_detection_candidates(const std::vector<PersonDetection>& detections,
                                                       const cv::Rect2f& user_box, size_t max_count) {
  std::vector<PersonDetection> out;
  if (user_box.area() <= 0) {
    out.assign(detections.begin(), detections.begin() + static_cast<std::ptrdiff_t>(std::min(max_count, detections.size())));
    return out;
  }
  std::vector<std::pair<float, const PersonDetection*>> ranked;
  const float box_centre_x = user_box.x + user_box.width / 2;
  for (const PersonDetection& d : detections) {
    const cv::Point2f hips = d.keypoints[person_keypoint::kHipCentre];
    if (!user_box.contains(hips)) continue;
    const cv::Point2f top = d.keypoints[person_keypoint::kBodyScale];
    const cv::Point2f v = top - hips;
    const float body = 2.0f * std::sqrt(v.x * v.x + v.y * v.y);
    const float off_centre = std::abs((hips.x + top.x) / 2 - box_centre_x) / user_box.width;
    const float off_size = body > 0 ? std::abs(std::log(body / user_box.height)) : std::numeric_limits<float>::infinity();
    ranked.emplace_back(off_centre + off_size, &d);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < ranked.size() && i < max_count; ++i) out.push_back(*ranked[i].second);
  return out;
}

std::optional<PersonDetection> choose_user_detection(const std::vector<PersonDetection>& detections,
                                                     const cv::Rect2f& user_box) {
  const std::vector<PersonDetection> c = user_detection_candidates(detections, user_box, 1);
  if (c.empty()) return std::nullopt;
  return c.front();
}

PoseRoi box_roi(const cv::Rect2f& user_box, float scale) {
  PoseRoi roi;
  roi.centre = cv::Point2f(user_box.x + user_box.width / 2, user_box.y + user_box.height / 2);
  roi.size = std::max(user_box.width, user_box.height) * scale;
  return roi;
}

double landmarks_box_iou(const PoseLandmarks& landmarks, const cv::Rect2f& user_box) {
  float x0 = landmarks[0].x, y0 = landmarks[0].y, x1 = x0, y1 = y0;
  for (const PoseLandmark& l : landmarks) {
    x0 = std::min(x0, l.x), y0 = std::min(y0, l.y);
    x1 = std::max(x1, l.x), y1 = std::max(y1, l.y);
  }
  return iou(cv::Rect2d(x0, y0, x1 - x0, y1 - y0), cv::Rect2d(user_box));
}

PoseEstimator::PoseEstimator(const PoseParams& params, PoseModels models)
    : params_(params),
      detector_(params, std::move(models.detector)),
      landmark_(std::move(models.landmark)),
      smoothing_(params.smoothing) {}

void PoseEstimator::reset() {
  next_roi_.reset();
  roi_correction_ = RoiCorrection{};
  smoothing_.reset();
}

PoseResult PoseEstimator::lost(PoseResult r) {
  reset();
  r.found = false;
  r.landmarks = PoseLandmarks{};
  r.counters = counters_;
  return r;
}

std::optional<PoseEstimator::Seed> PoseEstimator::seed(const cv::Mat& bgr, const cv::Rect2f& user_box, bool& nonfinite) {
  ++counters_.detector_runs;
  const bool boxed = user_box.area() > 0;
  // The region grows by seed_margin of the box height on every side (a share of the width would hardly widen a
  // tall thin box, and the detector needs the person's surroundings: arms stretched out, the head).
  const float grow = static_cast<float>(params_.seed_margin) * user_box.height;
  const cv::Rect2f region = boxed ? cv::Rect2f(user_box.x - grow, user_box.y - grow, user_box.width + 2 * grow,
                                               user_box.height + 2 * grow)
                                  : cv::Rect2f();
  const std::vector<PersonDetection> found = detector_.detect(bgr, region);
  if (detector_.last_nonfinite() > 0) {
    nonfinite = true;
    return std::nullopt;
  }
  // Without a box there is nothing to match: the best-scoring detection, as MediaPipe.
  const size_t tries = boxed ? static_cast<size_t>(params_.seed_candidates) : 1;
  std::optional<Seed> best;
  double best_match = -1.0;
  bool any_nonfinite = false;
  auto try_roi = [&](const PoseRoi& roi) {
    if (!(roi.size >= kMinRoiSide)) return;
    LandmarkOutput out = landmark_.run(bgr, roi);
    if (!out.finite) {
      any_nonfinite = true;
      return;
    }
    if (out.pose_flag < params_.pose_flag_threshold) return;
    const double match = boxed ? landmarks_box_iou(out.landmarks, user_box) : 0.0;
    if (!best || match > best_match) best_match = match, best = Seed{roi, out};
  };
  for (const PersonDetection& d : user_detection_candidates(found, user_box, tries))
    try_roi(roi_from_alignment(d.keypoints[person_keypoint::kHipCentre], d.keypoints[person_keypoint::kBodyScale],
                               static_cast<float>(params_.roi_scale)));
  // No detection gave a pose (none in the box, or the pose flag below the threshold): the box's own ROI.
  if (!best && boxed && params_.box_roi_scale > 0) try_roi(box_roi(user_box, static_cast<float>(params_.box_roi_scale)));
  // A net's NaN/Inf counts when it cost the frame its pose.
  nonfinite = any_nonfinite && !best;
  return best;
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
  LandmarkOutput out;
  if (roi) {
    ++counters_.frames_tracked;
    if (!(roi->size >= kMinRoiSide)) return lost(r);
    r.roi = *roi;
    out = landmark_.run(bgr, *roi);
    if (!out.finite) {
      ++counters_.nonfinite_outputs;
      r.nonfinite = true;
      return lost(r);
    }
    if (out.pose_flag < params_.pose_flag_threshold && params_.reseed_in_frame) {
      // The detector in the same frame; when its ROI finds the pose, the track corrects the auxiliary points'
      // ROIs by what separates the two from now on.
      ++counters_.reseeds;
      bool nonfinite = false;
      r.detector_ran = true;
      const std::optional<Seed> s = seed(bgr, user_box, nonfinite);
      if (nonfinite) ++counters_.nonfinite_outputs;  // as a seeding frame's: the frame is refused, not read
      r.nonfinite = nonfinite;
      if (s) {
        ++counters_.reseeds_found;
        roi_correction_.shift = s->roi.centre - aux_roi_.centre;
        roi_correction_.scale = aux_roi_.size > 0 ? s->roi.size / aux_roi_.size : 1.0f;
        roi_correction_.turn = normalize_radians(s->roi.rotation - aux_roi_.rotation);
        r.roi = s->roi;
        out = s->out;
      }
    }
  } else {
    bool nonfinite = false;
    r.detector_ran = true;
    const std::optional<Seed> s = seed(bgr, user_box, nonfinite);
    if (nonfinite) ++counters_.nonfinite_outputs;
    r.nonfinite = nonfinite;
    if (!s) return lost(r);
    r.roi = s->roi;
    out = s->out;
  }
  r.pose_flag = out.pose_flag;
  if (out.pose_flag < params_.pose_flag_threshold) return lost(r);
  smoothing_.apply(out.landmarks, out.aux, utime);
  aux_roi_ = roi_from_alignment(out.aux[0], out.aux[1], static_cast<float>(params_.roi_scale));
  next_roi_ = PoseRoi{aux_roi_.centre + roi_correction_.shift, aux_roi_.size * roi_correction_.scale,
                      normalize_radians(aux_roi_.rotation + roi_correction_.turn)};
  r.found = true;
  r.landmarks = out.landmarks;
  r.counters = counters_;
  return r;
}

}  // namespace gpilot
