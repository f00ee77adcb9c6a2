// The synthetic person's body: fixed proportions and the 3-D joint positions of a pose, in the person's own
// frame (metres; x to the person's left, y up from the ground, z forward, the way the person faces).
//
// The proportions are chosen against the tracker's head-body ratio (TrackerParams: body box = 2.75 face
// widths wide, 7 face heights tall, its top 0.25 face heights above the face box): with the default face box
// of 0.17 m that box spans x = ±0.234 m and y = 0.5525 .. 1.7425 m. Torso, resting arms and resting hands lie
// inside it (hands at rest: x = ±0.16 m, y ≈ 0.80 m, 0.043 m half-width); a stretched-out hand reaches
// 0.8 m sideways, far outside it. A dark turtleneck covers the neck so that no skin sits between the face
// and the shirt (where the hands stage would take it for a hand in front of the body).
#pragma once

#include <opencv2/core.hpp>

#include "scenario.hpp"

namespace gpilot {

// All lengths in metres, for a face box side of kReferenceFaceBox; FigureDims::scaled() rescales.
struct FigureDims {
  static constexpr double kReferenceFaceBox = 0.17;
  double face_box = 0.17;          //!< side of the Haar face box (the face photo is scaled to it)
  double face_top = 1.70;          //!< height of the face box's top edge
  double shoulder_y = 1.44;        //!< height of the shoulder joints
  double shoulder_x = 0.16;        //!< shoulder joints at ±x
  double torso_top = 1.47;         //!< top of the shoulders
  double torso_half_top = 0.185;   //!< half-width at the shoulders
  double waist_y = 1.05, torso_half_waist = 0.145;
  double hip_y = 0.88, torso_half_hip = 0.155;
  double neck_half = 0.055;        //!< turtleneck half-width
  double leg_x = 0.085;            //!< hip joints at ±x
  double foot_x = 0.10;            //!< ankles at ±x
  double ankle_y = 0.07;
  double leg_half_top = 0.07, leg_half_ankle = 0.048;
  double upper_arm = 0.30, forearm = 0.26, hand_offset = 0.085;  //!< wrist to hand centre along the forearm
  double upper_arm_half = 0.038, forearm_half = 0.031;
  double sleeve = 0.6;             //!< fraction of the upper arm the short sleeve covers
  double hand_length = 0.17, hand_half_width = 0.043;

  double arm_length() const { return upper_arm + forearm + hand_offset; }
  FigureDims scaled(double face_box_m) const;
};

// One arm's joints (person frame).
struct ArmJoints {
  cv::Point3d shoulder, elbow, wrist, hand;  //!< hand = the hand's centre
  cv::Point3d hand_tip;                      //!< end of the fingers
};

struct FigurePose {
  ArmJoints right, left;   //!< the person's own right (x < 0) and left (x > 0)
  double step_x = 0.0;     //!< sideways offset already applied to every point
};

// Joints for a pose; step_m moves the whole person along x.
FigurePose pose_figure(const FigureDims& dims, const ArmPose& right, const ArmPose& left, double step_m);

// The hand centre of an arm pose relative to the shoulder: (out, up, forward) metres.
cv::Point3d hand_offset_of(const FigureDims& dims, const ArmPose& pose);

}  // namespace gpilot
