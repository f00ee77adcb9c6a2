// Weighted non-maximum suppression as MediaPipe's NonMaxSuppressionCalculator (algorithm WEIGHTED, IoU
// overlap): the best remaining detection and every one overlapping it by more than the threshold are merged
// into one, box and keypoints averaged with the scores as weights; the merged detection keeps the best score.
#pragma once

#include <vector>

#include "person_detection.hpp"

namespace gpilot {

// Intersection over union of the two face boxes; 0 for boxes without area.
float face_iou(const PersonDetection& a, const PersonDetection& b);

// Merged detections, best score first. Equal scores keep their input order (the result is deterministic).
std::vector<PersonDetection> weighted_nms(std::vector<PersonDetection> detections, float iou_threshold);

}  // namespace gpilot
