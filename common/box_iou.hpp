// Intersection over union of two boxes: the tracker's score against ground truth (gpilot-eval-tracker's OTB
// measures, gpilot-report's track against the truth, the tracker tests).
#pragma once

#include <opencv2/core.hpp>

namespace gpilot {

// 0 when either box is empty (no width or height).
inline double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  if (!(a.width > 0 && a.height > 0 && b.width > 0 && b.height > 0)) return 0.0;
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

}  // namespace gpilot
