// What the paper's rules say about a frame when the true user box and the true hand positions are known:
// the ground truth's expected hand observation (Alg. 1 / Alg. 2) and command (Alg. 3 on a steady gesture).
//
// Simplifications against the real hands stage, which sees skin pixels and not hands:
// - a hand is a point (its centre); F_skin is taken equal for every hand (a full hand square), so the
//   argmax of Alg. 1 reduces to the largest |p_uc.x - p.x| + λ2 (p_uc.y - p.y) among the hands outside the
//   user box, and that of Alg. 2 to the smallest |p_bc.x - p.x| among the hands inside it;
// - Alg. 1 sees a hand outside the box only inside the search rectangle (hands.roi_extend_*) and the image;
// - Alg. 2 does not see a hand whose centre lies in the removed face/neck or legs band (hands.*_remove_ratio),
//   nor one within hands.neck_in_faces face heights below the box's face (the stage, with the user's face known);
// - the forearm's skin is ignored (the real Alg. 1 may pick a point on a raised forearm, not the hand);
// - as the stage (hands.needs_body_centre), while the body centre's hand square is out of the image no hand in
//   front is seen, nor a hand below the shoulders whose square the border cuts wherever on the hand (a square
//   of hand_size about its centre) it sits: such a gesture is not in view.
// The command is what Alg. 3 gives once the buffers are full of this frame's observation: OUT -> FINE, or
// UP/DOWN when |y| > |λ4 x| (x then 0); FRONT -> CLOSER (y < 0, z = +1) or FURTHER (y > 0, z = -1); else HOVER.
#pragma once

#include <array>

#include <opencv2/core.hpp>

#include "decide/decide_params.hpp"
#include "hands/hands_params.hpp"
#include "tracker/tracker_params.hpp"

namespace gpilot {

// The stage parameters the ground truth is computed with (their defaults unless the service passes config).
struct TruthRules {
  TrackerParams tracker;
  HandsParams hands;
  DecideParams decide;
};

// The tracker's body box from a face box (TrackerParams: head-body ratio), the ground truth's user box.
cv::Rect2f user_box_from_face(const cv::Rect2f& face, const TrackerParams& tracker);

struct ExpectedCommand {
  cv::Point2f shoulder_centre;  //!< p_uc: box centre x, hands.shoulder_centre_ratio of the height below the top
  cv::Point2f body_centre;      //!< p_bc: box centre x, hands.body_centre_ratio of the height below the top
  int kind = 0;                 //!< hand_obs_t::KIND_*
  cv::Point2f vector;           //!< pixels, hand - p_uc (OUT) or hand - p_bc (FRONT), else 0
  int mode = 0;                 //!< gesture_cmd_t::MODE_*
  cv::Point3f direction;        //!< x, y = vector / box width (x = 0 for UP/DOWN); z = +1 CLOSER, -1 FURTHER
};

// hands: the true centres of both hands, pixels; image: the frame size; hand_size: the side of a square about
// each centre that holds the whole hand, pixels (0: a hand is its centre).
ExpectedCommand expected_command(const cv::Rect2f& user_box, const std::array<cv::Point2f, 2>& hands,
                                 const cv::Size& image, const TruthRules& rules, float hand_size = 0.0f);

}  // namespace gpilot
