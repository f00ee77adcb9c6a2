// What the paper's rules say about a frame when the true user box and the true hand positions are known:
// the ground truth's expected hand observation (Alg. 1 / Alg. 2) and command (Alg. 3 on a steady gesture).
// The truth is the scene's: its rules are the fixed constants below (the paper's numbers where it gives them,
// else the stage's defaults as they stood when the truth was fixed), never the config of the stages it judges,
// so a mis-set stage scores lower instead of moving its truth along.
//
// p_uc and p_bc are the person's own (the figure's shoulder joints, and midway from them to its hip joints), which
// the paper estimates on the box (0.2 and 0.5 of its height) and the pose method from landmarks.
// Simplifications against the real hands stage, which sees skin pixels and not hands:
// - a hand is a point (its centre); F_skin is taken equal for every hand (a full hand square), so the
//   argmax of Alg. 1 reduces to the largest |p_uc.x - p.x| + λ2 (p_uc.y - p.y) among the hands outside the
//   user box, and that of Alg. 2 to the smallest |p_bc.x - p.x| among the hands inside it;
// - Alg. 1 sees a hand outside the box only within an arm's reach of it (kReachSide, kReachTop, kReachBottom)
//   and in the image;
// - Alg. 2 does not see a hand whose centre lies in the face/neck or legs band of the box, nor one within
//   kNeckInFaces face heights below the box's face (the box is made from the true face, so that face is its head);
// - the forearm's skin is ignored (the real Alg. 1 may pick a point on a raised forearm, not the hand);
// - while the body centre's hand square is out of the image no hand in front can be judged (higher or lower
//   than a centre out of view is unknown), nor a hand below the shoulders whose square the border cuts
//   wherever on the hand (a square of hand_size about its centre) it sits: such a gesture is not in view.
// The command is what Alg. 3 gives once the buffers are full of this frame's observation: OUT -> FINE, or
// UP/DOWN when |y| > |λ4 x| (x then 0); FRONT -> CLOSER (y < 0, z = +1) or FURTHER (y > 0, z = -1); else HOVER.
#pragma once

#include <array>
#include <optional>

#include <opencv2/core.hpp>

namespace gpilot {

// The ground truth's rules (fixed: the scene's, not a stage's config).
namespace truth_rules {
constexpr double kShoulderCentreRatio = 0.2;  // p_uc: this fraction of the box height below its top (the shoulders)
constexpr double kBodyCentreRatio = 0.5;      // p_bc: the box centre (the paper)
constexpr double kHandSquareRatio = 0.25;     // hand square side / box width (the paper's w/4)
constexpr double kReachSide = 1.2;            // a stretched-out hand lies within this many box widths beside the box
constexpr double kReachTop = 0.25;            // ... this many box heights above it (an arm raised high)
constexpr double kReachBottom = 0.0;          // ... and not below it (the feet end the box)
constexpr double kFaceBandRatio = 0.2;        // the top of the box is face and neck: no hand in front there
constexpr double kLegsBandRatio = 0.35;       // the bottom of the box is legs and feet (below the hips)
constexpr double kNeckInFaces = 0.35;         // the neck reaches this many face heights below the face
constexpr double kFrontGateRatio = 0.2;       // Alg. 2: a hand in front lies within w/5 of p_bc in x (the paper)
constexpr double kLambda2 = 0.2;              // Alg. 1's weight of the height above p_uc (the paper's λ2)
constexpr double kLambda4 = 0.5;              // Alg. 3: UP/DOWN when |y| > |λ4 x| (the paper's λ4)
}  // namespace truth_rules

// Where the person's shoulders and torso are in the image (the scene knows its figure's joints): p_uc the
// shoulder joints' midpoint, p_bc midway between it and the hip joints' midpoint.
struct TorsoCentres {
  cv::Point2f shoulder_centre, body_centre;
};

struct ExpectedCommand {
  cv::Point2f shoulder_centre;  //!< p_uc: the given TorsoCentres', else box centre x, kShoulderCentreRatio of the height below the top
  cv::Point2f body_centre;      //!< p_bc: the given TorsoCentres', else box centre x, kBodyCentreRatio of the height below the top
  int kind = 0;                 //!< hand_obs_t::KIND_*
  cv::Point2f vector;           //!< pixels, hand - p_uc (OUT) or hand - p_bc (FRONT), else 0
  int mode = 0;                 //!< gesture_cmd_t::MODE_*
  cv::Point3f direction;        //!< x, y = vector / box width (x = 0 for UP/DOWN); z = +1 CLOSER, -1 FURTHER
};

// user_box: the true body box (body_from_face of the true face with the preset head-body ratios, BodyProportions).
// hands: the true centres of both hands, pixels; image: the frame size; hand_size: the side of a square about
// each centre that holds the whole hand, pixels (0: a hand is its centre); centres: p_uc and p_bc where the
// person's joints put them (none: where the paper puts them on the box).
ExpectedCommand expected_command(const cv::Rect2f& user_box, const std::array<cv::Point2f, 2>& hands,
                                 const cv::Size& image, float hand_size = 0.0f,
                                 const std::optional<TorsoCentres>& centres = std::nullopt);

}  // namespace gpilot
