// The paper's Alg. 1, 2 and 3 applied to true hand positions (see gesture_truth.hpp for the simplifications).
#include "gesture_truth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "body_proportions.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "hand_square.hpp"

namespace gpilot {
namespace {

bool inside(const cv::Point2f& p, float x0, float y0, float x1, float y1) {
  return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
}

}  // namespace

ExpectedCommand expected_command(const cv::Rect2f& box, const std::array<cv::Point2f, 2>& hands,
                                 const cv::Size& image, float hand_size, const std::optional<TorsoCentres>& centres) {
  using namespace truth_rules;
  ExpectedCommand e;
  const float cx = box.x + 0.5f * box.width;
  e.shoulder_centre = centres ? centres->shoulder_centre : cv::Point2f(cx, static_cast<float>(box.y + kShoulderCentreRatio * box.height));
  e.body_centre = centres ? centres->body_centre : cv::Point2f(cx, static_cast<float>(box.y + kBodyCentreRatio * box.height));
  e.kind = hand_obs_t::KIND_NONE;
  e.mode = gesture_cmd_t::MODE_HOVER;
  const float x1 = box.x + box.width, y1 = box.y + box.height;
  // With the body centre out of view (the drone high and close, the hips below the frame) no hand in front can
  // be judged, nor a hand below the shoulders whose square the border cuts wherever it sits on the hand (the
  // stage's hand pixel is the hand's outer edge, not its centre: a DOWN hand whose centre's square the border
  // cut was seen and flown, and judged a false DOWN).
  const int side = hand_square_side(kHandSquareRatio, box.width, image);
  const bool cut_body = !square_in_view(e.body_centre, side, image);
  const auto border_cut = [&](const cv::Point2f& p) {
    return cut_body && p.y > e.shoulder_centre.y && square_cut_by_side_or_bottom(p, side, image, 0.5f * std::max(0.0f, hand_size));
  };

  // Alg. 1: a hand outside the box (but within an arm's reach of it and in the image).
  const float rx0 = static_cast<float>(std::max(0.0, box.x - kReachSide * box.width));
  const float rx1 = static_cast<float>(std::min<double>(image.width, x1 + kReachSide * box.width));
  const float ry0 = static_cast<float>(std::max(0.0, box.y - kReachTop * box.height));
  const float ry1 = static_cast<float>(std::min<double>(image.height, y1 + kReachBottom * box.height));
  double best = -std::numeric_limits<double>::infinity();
  for (const auto& p : hands) {
    if (inside(p, box.x, box.y, x1, y1) || !inside(p, rx0, ry0, rx1, ry1) || border_cut(p)) continue;
    const double score = std::fabs(e.shoulder_centre.x - p.x) + kLambda2 * (e.shoulder_centre.y - p.y);
    if (score > best) {
      best = score;
      e.kind = hand_obs_t::KIND_OUT;
      e.vector = p - e.shoulder_centre;
    }
  }
  if (e.kind == hand_obs_t::KIND_OUT) {
    float x = e.vector.x;
    const float y = e.vector.y;
    if (std::fabs(y) > std::fabs(kLambda4 * x)) {
      x = 0.0f;
      e.mode = y < 0 ? gesture_cmd_t::MODE_UP : gesture_cmd_t::MODE_DOWN;
    } else {
      e.mode = gesture_cmd_t::MODE_FINE;
    }
    e.direction = {x / box.width, y / box.width, 0.0f};
    return e;
  }

  // Alg. 2: a hand inside the box, below the face and neck and above the legs, near the midline. The box is made
  // from the true face with the preset ratios, so that face is the box's own head.
  if (cut_body) return e;
  const cv::Rect2d face = face_from_body(box, BodyProportions{});
  const float band0 = static_cast<float>(
      std::max(box.y + kFaceBandRatio * box.height, neck_end_y(kNeckInFaces, face.y, face.height)));
  const float band1 = static_cast<float>(y1 - kLegsBandRatio * box.height);
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
  if (nearest < kFrontGateRatio * box.width) {
    e.vector = chosen - e.body_centre;
    e.kind = hand_obs_t::KIND_FRONT;
    if (e.vector.y != 0.0f) {
      e.mode = e.vector.y < 0 ? gesture_cmd_t::MODE_CLOSER : gesture_cmd_t::MODE_FURTHER;
      e.direction = {0.0f, 0.0f, e.vector.y < 0 ? 1.0f : -1.0f};
    }
  }
  return e;
}

}  // namespace gpilot
