// The paper's hand square (side = a ratio of the user box width) and whether the body centre with a hand square
// around it lies in the image. Shared by the hands stage (hand_geometry) and the synthetic world's ground truth
// (gesture_truth.hpp), each with its own ratios: both judge alike which hands the image border cuts.
#pragma once

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

namespace gpilot {

// Side in pixels: ratio x box width, at least 1, capped at what the image holds (beyond that a larger square
// changes nothing, while a hostile 1e6 px box would size one of gigabytes).
inline int hand_square_side(double ratio, double box_width, cv::Size image) {
  const double image_side = std::max(image.width, image.height);
  return std::max(1, static_cast<int>(std::lround(std::min(box_width * ratio, 2 * image_side + 1))));
}

// The skin pixels Alg. 1 or 2 need (more than this): the paper's count, or `share` of the hand square's area where
// that is less (a far user's hand fills less of the paper's count; share 0: the paper's count).
inline int min_hand_skin(int paper, double share, int side) {
  const double square = share * side * side;
  return share > 0 && square < paper ? static_cast<int>(square) : paper;
}

// Where the neck below a known face ends: neck_in_faces face heights below its bottom.
inline double neck_end_y(double neck_in_faces, double face_y, double face_height) {
  return face_y + face_height * (1.0 + neck_in_faces);
}

// The square of side `side` centred at p lies wholly in the image.
inline bool square_in_view(cv::Point2f p, int side, cv::Size image) {
  const double half = side / 2.0;
  return p.x - half >= 0 && p.y - half >= 0 && p.x + half <= image.width && p.y + half <= image.height;
}

// The square of side `side` at p, as F_skin counts it ([p - side/2, p - side/2 + side)), crosses the image's left,
// right or bottom border: below the shoulders, while the body centre is out of view, no hand is judged there.
// give: the square may move this far towards the image's inside first (the ground truth's hand is a square of
// its own about p: a part of it whose square the border does not cut is a hand the stage can judge).
inline bool square_cut_by_side_or_bottom(cv::Point2f p, int side, cv::Size image, float give = 0.0f) {
  const int half = side / 2;
  return p.x + give - half < 0 || p.x - give - half + side > image.width || p.y - give - half + side > image.height;
}

}  // namespace gpilot
