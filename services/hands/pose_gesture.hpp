// The paper's observation (HAND_OBS) read from body landmarks instead of skin: each arm is stretched out (OUT),
// in front of the torso (FRONT), at rest, or doing something else; the person's observation is the one arm that
// commands (two commanding arms are no command). Vectors as the paper's: OUT from the shoulder centre p_uc, FRONT from the body
// centre p_bc, image pixels. Pure and stateless: the same landmarks give the same observation.
#pragma once

#include <optional>
#include <string>

#include <opencv2/core/types.hpp>

#include "hands/hand_detector.hpp"
#include "hands/pose_gesture_params.hpp"
#include "pose/pose_landmarks.hpp"

namespace gpilot {

enum class ArmPose { Unseen = 0, Rest, Out, FrontHigh, FrontLow, Other };
const char* arm_pose_name(ArmPose a);

struct ArmReading {
  ArmPose pose = ArmPose::Unseen;
  cv::Point2f hand;               //!< the hand's point (wrist towards the knuckles), pixels
  double reach = 0;               //!< |W-S|, pixels
  double straightness = 0;        //!< |W-S| / (|S-E| + |E-W|)
  double from_down_deg = 0;       //!< angle between shoulder->wrist and image-down, 0..180
  double elbow_bend_deg = 0;      //!< angle between the upper arm and the forearm in the image, 0 (straight)..180
  bool wrist_between_hips = false;        //!< the wrist between the hips in x
  bool hand_beside_box = false;   //!< the hand's point outside the user box
};

struct PoseGesture {
  HandKind kind = HandKind::None;
  cv::Point2f vector;             //!< hand - p_uc (OUT) or hand - p_bc (FRONT), pixels; zero for NONE
  cv::Point2f hand;               //!< the commanding hand's point, pixels (NONE: none)
  cv::Point2f shoulder_centre;    //!< p_uc: the shoulders' midpoint
  cv::Point2f body_centre;        //!< p_bc: midway between the shoulders' and the hips' midpoints
  bool torso_seen = false;        //!< the shoulders visible: without them there is no observation (without the hips
                                  //!< no hand in front)
  ArmReading left, right;         //!< the person's own left and right arm
  const char* rule = "";          //!< which rule decided the person's observation
};

// user_box: the tracker's box of the user (the paper's Alg. 1 calls a hand beside it out; its width sizes the
// hand square), pixels; none: not used.
// frame: the image's size (hips on its bottom edge are not seen, hips near it may be placed too high, and a hand
// at it of a body cut above the hips is not read); none: not used.
PoseGesture read_pose_gesture(const PoseLandmarks& lm, const PoseGestureParams& p,
                              const std::optional<cv::Rect2f>& user_box = std::nullopt,
                              const std::optional<cv::Size>& frame = std::nullopt);

// "rule; left POSE (s straightness, angle from down[, between the hips]), right ...": what decided, for CSVs and logs.
std::string describe_pose_gesture(const PoseGesture& g);

}  // namespace gpilot
