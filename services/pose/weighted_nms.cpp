// NonMaxSuppressionCalculator's WeightedNonMaxSuppression, on our PersonDetection.
#include "weighted_nms.hpp"

#include <algorithm>

#include "box_iou.hpp"

namespace gpilot {

float face_iou(const PersonDetection& a, const PersonDetection& b) {
  return static_cast<float>(iou(cv::Rect2d(a.face), cv::Rect2d(b.face)));
}

std::vector<PersonDetection> weighted_nms(std::vector<PersonDetection> detections, float iou_threshold) {
  std::stable_sort(detections.begin(), detections.end(),
                   [](const PersonDetection& a, const PersonDetection& b) { return a.score > b.score; });
  std::vector<PersonDetection> merged;
  std::vector<PersonDetection> remaining = std::move(detections);
  while (!remaining.empty()) {
    const PersonDetection best = remaining.front();
    std::vector<PersonDetection> rest;
    double total = 0.0, x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
    std::array<cv::Point2d, 4> keypoints{};
    for (const PersonDetection& d : remaining) {
      // The best one overlaps itself fully, so it is always among the merged.
      if (face_iou(d, best) <= iou_threshold && &d != &remaining.front()) {
        rest.push_back(d);
        continue;
      }
      total += d.score;
      x0 += static_cast<double>(d.face.x) * d.score;
      y0 += static_cast<double>(d.face.y) * d.score;
      x1 += static_cast<double>(d.face.x + d.face.width) * d.score;
      y1 += static_cast<double>(d.face.y + d.face.height) * d.score;
      for (size_t k = 0; k < keypoints.size(); ++k) keypoints[k] += cv::Point2d(d.keypoints[k]) * static_cast<double>(d.score);
    }
    PersonDetection out = best;
    if (total > 0.0) {
      out.face = cv::Rect2f(static_cast<float>(x0 / total), static_cast<float>(y0 / total),
                            static_cast<float>((x1 - x0) / total), static_cast<float>((y1 - y0) / total));
      for (size_t k = 0; k < keypoints.size(); ++k) out.keypoints[k] = cv::Point2f(keypoints[k] / total);
    }
    merged.push_back(out);
    remaining = std::move(rest);
  }
  return merged;
}

}  // namespace gpilot
