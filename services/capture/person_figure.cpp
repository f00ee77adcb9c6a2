// Joint positions of the synthetic person: the arm's direction from its pose, the elbow by two-link inverse
// kinematics (it bends down and back, the way an arm folds, and only a little outward so that a hand in
// front of the body keeps its elbow inside the tracker's body box).
#include "person_figure.hpp"

#include <algorithm>
#include <cmath>

namespace gpilot {
namespace {

constexpr double kDeg = M_PI / 180.0;

cv::Point3d unit(const cv::Point3d& v) {
  const double n = std::sqrt(v.dot(v));
  return n > 1e-12 ? v * (1.0 / n) : cv::Point3d(0, 0, 0);
}

// side = +1 for the left arm (outward is +x), -1 for the right.
ArmJoints solve_arm(const FigureDims& d, const ArmPose& pose, double side, double step_x) {
  ArmJoints j;
  j.shoulder = {side * d.shoulder_x + step_x, d.shoulder_y, 0.0};
  const cv::Point3d off = hand_offset_of(d, pose);
  j.hand = j.shoulder + cv::Point3d(side * off.x, off.y, off.z);

  const double l1 = d.upper_arm, l2 = d.forearm + d.hand_offset;
  const cv::Point3d to_hand = j.hand - j.shoulder;
  const double dist = std::clamp(std::sqrt(to_hand.dot(to_hand)), std::fabs(l1 - l2) + 1e-6, l1 + l2);
  const cv::Point3d u = unit(to_hand);
  const double a = (l1 * l1 - l2 * l2 + dist * dist) / (2.0 * dist);
  const double h = std::sqrt(std::max(0.0, l1 * l1 - a * a));
  cv::Point3d pole(side * 0.1, -1.0, -0.5);
  cv::Point3d n = unit(pole - u * pole.dot(u));
  if (n.dot(n) < 0.5) n = unit(cv::Point3d(0, 0, -1) - u * (-u.z));
  j.elbow = j.shoulder + u * a + n * h;
  const cv::Point3d fore = unit(j.hand - j.elbow);
  j.wrist = j.hand - fore * d.hand_offset;
  j.hand_tip = j.hand + fore * (d.hand_length * 0.5);
  return j;
}

}  // namespace

FigureDims FigureDims::scaled(double face_box_m) const {
  const double k = face_box_m / kReferenceFaceBox;
  FigureDims s = *this;
  for (double* v : {&s.face_box, &s.face_top, &s.shoulder_y, &s.shoulder_x, &s.torso_top, &s.torso_half_top,
                    &s.waist_y, &s.torso_half_waist, &s.hip_y, &s.torso_half_hip, &s.neck_half, &s.leg_x,
                    &s.foot_x, &s.ankle_y, &s.leg_half_top, &s.leg_half_ankle, &s.upper_arm, &s.forearm,
                    &s.hand_offset, &s.upper_arm_half, &s.forearm_half, &s.hand_length, &s.hand_half_width})
    *v *= k;
  return s;
}

cv::Point3d hand_offset_of(const FigureDims& d, const ArmPose& pose) {
  const double a = pose.angle_deg * kDeg, f = pose.forward_deg * kDeg;
  const double r = std::clamp(pose.extension, 0.3, 1.0) * d.arm_length();
  return {r * std::sin(a) * std::cos(f), -r * std::cos(a) * std::cos(f), r * std::sin(f)};
}

FigurePose pose_figure(const FigureDims& dims, const ArmPose& right, const ArmPose& left, double step_m) {
  FigurePose p;
  p.step_x = step_m;
  p.right = solve_arm(dims, right, -1.0, step_m);
  p.left = solve_arm(dims, left, +1.0, step_m);
  return p;
}

}  // namespace gpilot
