// pose_landmark_filtering.pbtxt's LandmarksSmoothingCalculator and VisibilitySmoothingCalculator nodes.
#include "landmark_smoothing.hpp"

#include <algorithm>

namespace gpilot {
namespace {

// MediaPipe's min_allowed_object_scale: below it (all points on one spot) the points pass unsmoothed.
constexpr double kMinObjectScale = 1e-6;

template <class Points>
double object_scale(const Points& points) {
  float x0 = points[0].x, x1 = x0, y0 = points[0].y, y1 = y0;
  for (const auto& p : points) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  return (static_cast<double>(x1 - x0) + static_cast<double>(y1 - y0)) / 2.0;
}

}  // namespace

LandmarkSmoothing::LandmarkSmoothing(const PoseSmoothingParams& params)
    : params_(params),
      landmark_filters_(3 * kPoseLandmarkCount, OneEuroFilter(params.landmarks, params.first_rate_hz)),
      aux_filters_(2 * 2, OneEuroFilter(params.aux, params.first_rate_hz)) {}

void LandmarkSmoothing::reset() {
  for (OneEuroFilter& f : landmark_filters_) f.reset();
  for (OneEuroFilter& f : aux_filters_) f.reset();
  visibility_started_ = false;
}

void LandmarkSmoothing::apply(PoseLandmarks& landmarks, std::array<cv::Point2f, 2>& aux, int64_t utime) {
  if (!params_.enabled) return;
  // Visibility first, as the graph: new = alpha value + (1 - alpha) previous (presence is not smoothed).
  const float alpha = static_cast<float>(params_.visibility_alpha);
  for (size_t i = 0; i < landmarks.size(); ++i) {
    if (visibility_started_) landmarks[i].visibility = alpha * landmarks[i].visibility + (1.0f - alpha) * visibility_[i];
    visibility_[i] = landmarks[i].visibility;
  }
  visibility_started_ = true;
  const double scale = object_scale(landmarks);
  if (scale >= kMinObjectScale) {
    for (int i = 0; i < kPoseLandmarkCount; ++i) {
      PoseLandmark& l = landmarks[static_cast<size_t>(i)];
      OneEuroFilter* f = &landmark_filters_[static_cast<size_t>(3 * i)];
      l.x = static_cast<float>(f[0].apply(l.x, utime, 1.0 / scale));
      l.y = static_cast<float>(f[1].apply(l.y, utime, 1.0 / scale));
      l.z = static_cast<float>(f[2].apply(l.z, utime, 1.0 / scale));
    }
  }
  const double aux_scale = object_scale(aux);
  if (aux_scale >= kMinObjectScale) {
    for (size_t i = 0; i < aux.size(); ++i) {
      aux[i].x = static_cast<float>(aux_filters_[2 * i].apply(aux[i].x, utime, 1.0 / aux_scale));
      aux[i].y = static_cast<float>(aux_filters_[2 * i + 1].apply(aux[i].y, utime, 1.0 / aux_scale));
    }
  }
}

}  // namespace gpilot
