// The paper's observation (HAND_OBS) read from body landmarks instead of skin: each arm is stretched out (OUT),
// in front of the torso (FRONT), at rest, or doing something else; the person's observation is the one arm that
// commands (two commanding arms are no command). Vectors as the paper's: OUT from the shoulder centre p_uc, FRONT from the body
// centre p_bc, image pixels. Pure and stateless: the same landmarks give the same observation.
#pragma once

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
  double straightness = 0;        //!< |W-S| / (|S-E| + |E-W|)
  double from_down_deg = 0;       //!< angle between shoulder->wrist and image-down, 0..180
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

PoseGesture read_pose_gesture(const PoseLandmarks& lm, const PoseGestureParams& p);

}  // namespace gpilot
