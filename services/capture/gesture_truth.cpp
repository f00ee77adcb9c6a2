// The paper's Alg. 1, 2 and 3 applied to true hand positions (see gesture_truth.hpp for the simplifications).
#include "gesture_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "body_proportions.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "hands/hand_square.hpp"

namespace gpilot {
namespace {

bool inside(const cv::Point2f& p, float x0, float y0, float x1, float y1) {
  return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
}

}  // namespace

cv::Rect2f user_box_from_face(const cv::Rect2f& face, const TrackerParams& t) {
  const float w = static_cast<float>(face.width * t.body_width_in_faces);
  const float h = static_cast<float>(face.height * t.body_height_in_faces);
  const float cx = face.x + face.width * 0.5f;
  return {cx - 0.5f * w, static_cast<float>(face.y - t.body_top_in_faces * face.height), w, h};
}

ExpectedCommand expected_command(const cv::Rect2f& box, const std::array<cv::Point2f, 2>& hands,
                                 const cv::Size& image, const TruthRules& rules, float hand_size) {
  const HandsParams& hp = rules.hands;
  ExpectedCommand e;
  const float cx = box.x + 0.5f * box.width;
  e.shoulder_centre = {cx, static_cast<float>(box.y + hp.shoulder_centre_ratio * box.height)};
  e.body_centre = {cx, static_cast<float>(box.y + hp.body_centre_ratio * box.height)};
  e.kind = hand_obs_t::KIND_NONE;
  e.mode = gesture_cmd_t::MODE_HOVER;
  const float x1 = box.x + box.width, y1 = box.y + box.height;
  // As the stage (hands.needs_body_centre): with the body centre out of view (the drone high and close, the hips
  // below the frame) no hand in front is judged, nor a hand below the shoulders whose square the border cuts
  // wherever it sits on the hand (the stage's hand pixel is the hand's outer edge, not its centre: a DOWN hand
  // whose centre's square the border cut was seen and flown, and judged a false DOWN).
  const int side = hand_square_side(hp, box.width, image);
  const bool cut_body = hp.needs_body_centre && !square_in_view(e.body_centre, side, image);
  const auto border_cut = [&](const cv::Point2f& p) {
    return cut_body && p.y > e.shoulder_centre.y && square_cut_by_side_or_bottom(p, side, image, 0.5f * std::max(0.0f, hand_size));
  };

  // Alg. 1: a hand outside the box (but inside the search rectangle and the image).
  const float rx0 = static_cast<float>(std::max(0.0, box.x - hp.roi_extend_side * box.width));
  const float rx1 = static_cast<float>(std::min<double>(image.width, x1 + hp.roi_extend_side * box.width));
  const float ry0 = static_cast<float>(std::max(0.0, box.y - hp.roi_extend_top * box.height));
  const float ry1 = static_cast<float>(std::min<double>(image.height, y1 + hp.roi_extend_bottom * box.height));
  double best = -std::numeric_limits<double>::infinity();
  for (const auto& p : hands) {
    if (inside(p, box.x, box.y, x1, y1) || !inside(p, rx0, ry0, rx1, ry1) || border_cut(p)) continue;
    const double score = std::fabs(e.shoulder_centre.x - p.x) + hp.lambda2 * (e.shoulder_centre.y - p.y);
    if (score > best) {
      best = score;
      e.kind = hand_obs_t::KIND_OUT;
      e.vector = p - e.shoulder_centre;
    }
  }
  if (e.kind == hand_obs_t::KIND_OUT) {
    float x = e.vector.x;
    const float y = e.vector.y;
    if (std::fabs(y) > std::fabs(rules.decide.lambda4 * x)) {
      x = 0.0f;
      e.mode = y < 0 ? gesture_cmd_t::MODE_UP : gesture_cmd_t::MODE_DOWN;
    } else {
      e.mode = gesture_cmd_t::MODE_FINE;
    }
    e.direction = {x / box.width, y / box.width, 0.0f};
    return e;
  }

  // Alg. 2: a hand inside the box, in the band left after removing face/neck and legs, near the midline.
  if (cut_body) return e;
  // As the stage with the user's face known (hands.neck_in_faces): the rows down to neck_in_faces face heights
  // below the face are neck. The truth's box is made from the true face (user_box_from_face), so that face is
  // the box's own head.
  float band0 = static_cast<float>(box.y + hp.face_remove_ratio * box.height);
  if (hp.neck_in_faces > 0) {
    const cv::Rect2d face = face_from_body(box, rules.tracker.body());
    band0 = std::max(band0, static_cast<float>(neck_end_y(hp, face.y, face.height)));
  }
  const float band1 = static_cast<float>(y1 - hp.legs_remove_ratio * box.height);
  double nearest = std::numeric_limits<double>::infinity();
  cv::Point2f chosen;
  for (const auto& p : hands) {
    if (!inside(p, box.x, band0, x1, band1)) continue;
    const double cost = std::fabs(e.body_centre.x - p.x);
    if (cost < nearest) {
      nearest = cost;
      chosen = p;
    }
  }
  if (nearest < hp.front_gate_ratio * box.width) {
    e.vector = chosen - e.body_centre;
    if (e.vector.y != 0.0f) {
      e.kind = hand_obs_t::KIND_FRONT;
      e.mode = e.vector.y < 0 ? gesture_cmd_t::MODE_CLOSER : gesture_cmd_t::MODE_FURTHER;
      e.direction = {0.0f, 0.0f, e.vector.y < 0 ? 1.0f : -1.0f};
    } else {
      e.kind = hand_obs_t::KIND_FRONT;
    }
  }
  return e;
}

}  // namespace gpilot
