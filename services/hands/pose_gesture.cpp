#include "hands/pose_gesture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace gpilot {

namespace {

namespace L = pose_landmark;

double length(cv::Point2f v) { return std::hypot(static_cast<double>(v.x), static_cast<double>(v.y)); }

// y of the line through a and b at x (a vertical line: their mean y).
double line_y_at(cv::Point2f a, cv::Point2f b, double x) {
  const double dx = static_cast<double>(b.x) - a.x;
  if (std::abs(dx) < 1e-6) return (static_cast<double>(a.y) + b.y) / 2;
  return a.y + (x - a.x) * (static_cast<double>(b.y) - a.y) / dx;
}

// Angle between two vectors, degrees 0..180 (0 when either is zero).
double angle_deg(cv::Point2f u, cv::Point2f v) {
  const double nu = length(u), nv = length(v);
  if (nu == 0 || nv == 0) return 0.0;
  const double c = (static_cast<double>(u.x) * v.x + static_cast<double>(u.y) * v.y) / (nu * nv);
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

cv::Point2f at(const PoseLandmarks& lm, int i) { return {lm[i].x, lm[i].y}; }
bool seen(const PoseLandmarks& lm, int i, double min_visibility) { return lm[i].visibility >= min_visibility; }

// What the torso gives every arm's rules: its lines, centre, span and the face.
struct Torso {
  cv::Point2f left_shoulder, right_shoulder, left_hip, right_hip;
  cv::Point2f shoulder_mid, body_centre;
  double span_min_x = 0, span_max_x = 0;
  double shoulder_width = 0;  //!< pixels
  double height = 0;          //!< shoulders' midpoint to hips' midpoint, pixels
  cv::Point2f face;
  double face_radius = 0;  //!< pixels
  bool hips_seen = false;  //!< the hips visible: the hip line and p_bc are measured, not only predicted
  double low_from_y = 0;   //!< a hand in front below p_bc is judged only below this (p_bc, or lower where the
                           //!< hips may be placed too high)
  double cut_below_y = std::numeric_limits<double>::infinity();  //!< an arm's hand below the shoulders and
                                                                 //!< below this is not read (the body cut)
};

Torso torso_of(const PoseLandmarks& lm, const PoseGestureParams& p, const std::optional<cv::Rect2f>& user_box,
               const std::optional<cv::Size>& frame) {
  Torso t;
  t.left_shoulder = at(lm, L::kLeftShoulder);
  t.right_shoulder = at(lm, L::kRightShoulder);
  t.left_hip = at(lm, L::kLeftHip);
  t.right_hip = at(lm, L::kRightHip);
  t.shoulder_mid = (t.left_shoulder + t.right_shoulder) * 0.5f;
  const cv::Point2f hip_mid = (t.left_hip + t.right_hip) * 0.5f;
  t.body_centre = (t.shoulder_mid + hip_mid) * 0.5f;
  const double torso_height = length(hip_mid - t.shoulder_mid);
  t.height = torso_height;
  const auto xs = {t.left_shoulder.x, t.right_shoulder.x, t.left_hip.x, t.right_hip.x};
  t.span_min_x = std::min(xs) - p.span_margin * torso_height;
  t.span_max_x = std::max(xs) + p.span_margin * torso_height;
  // The face's centre: the mean of the nose, eyes and ears (0..8), whose landmarks the model places even when
  // they are turned away (the wrist test needs a centre, not a visible face).
  cv::Point2f sum;
  for (int i = L::kNose; i <= L::kRightEar; ++i) sum += at(lm, i);
  t.face = sum * (1.0f / static_cast<float>(L::kRightEar + 1));
  t.shoulder_width = length(t.left_shoulder - t.right_shoulder);
  t.face_radius = p.face_radius * t.shoulder_width;
  t.hips_seen = seen(lm, L::kLeftHip, p.hips_min_visibility) && seen(lm, L::kRightHip, p.hips_min_visibility);
  // Hips on the frame's bottom edge (the drone high and close) are the model's guess of a body cut off there, and
  // a hanging arm seen from above ends between them.
  const double lowest_hip = std::max(t.left_hip.y, t.right_hip.y);
  if (frame && lowest_hip > frame->height - p.hips_min_frame_margin * torso_height) t.hips_seen = false;
  // A body the edge cuts just below the hips has them placed inside the frame, visible, too high: p_bc then sits
  // higher than the person's, which can make a hand in front read lower, never higher.
  const bool hips_doubtful = frame && lowest_hip > frame->height - p.low_hips_min_frame_margin * torso_height;
  t.low_from_y = t.body_centre.y + (hips_doubtful ? 0.5 * p.low_hips_doubt * torso_height : 0.0);
  // The frame's bottom edge cutting the body above the hips (hips not seen) may cut a hanging arm too: the
  // model then places the wrist out of view inside the frame, near the edge, where an arm out and down has it.
  if (frame && user_box && !t.hips_seen) t.cut_below_y = frame->height - p.cut_hand_margin * user_box->width;
  return t;
}

ArmReading read_arm(const PoseLandmarks& lm, const Torso& t, const PoseGestureParams& p,
                    const std::optional<cv::Rect2f>& user_box, int shoulder, int elbow, int wrist, int pinky, int index) {
  ArmReading a;
  const cv::Point2f S = at(lm, shoulder), E = at(lm, elbow), W = at(lm, wrist);
  const cv::Point2f knuckles = (at(lm, pinky) + at(lm, index)) * 0.5f;
  a.hand = W + (knuckles - W) * static_cast<float>(p.hand_beyond_wrist);
  if (!(seen(lm, shoulder, p.min_visibility) && seen(lm, elbow, p.min_visibility) && seen(lm, wrist, p.min_visibility)))
    return a;  // Unseen
  const double path = length(E - S) + length(W - E);
  a.reach = length(W - S);
  a.straightness = path > 0 ? a.reach / path : 0.0;
  const cv::Point2f d = W - S;
  a.from_down_deg = (d.x == 0 && d.y == 0) ? 0.0 : std::abs(std::atan2(static_cast<double>(d.x), static_cast<double>(d.y))) * 180.0 / M_PI;
  const double shoulder_y = line_y_at(t.left_shoulder, t.right_shoulder, W.x);
  const double hip_y = line_y_at(t.left_hip, t.right_hip, W.x);
  const bool above_shoulders = W.y < shoulder_y, below_hips = W.y > hip_y;
  const bool below_centre = W.y > t.body_centre.y;
  const bool in_span = W.x >= t.span_min_x && W.x <= t.span_max_x;
  const bool at_face = length(W - t.face) <= t.face_radius;
  const bool straight = a.straightness >= p.out_min_straightness;
  // A straight arm nearer down than OUT hangs, unless its wrist lies between the hips in x: an arm cannot hang
  // through the body, so that hand is held in front of it (the hand low in front, seen from the front).
  // A hanging arm is straight at the elbow; a hand held low in front bends it (the forearm turns forward and in
  // to the belly), and its wrist may sit at a hip joint's x: for such an arm the hips' extent is grown a little.
  a.elbow_bend_deg = angle_deg(E - S, W - E);
  const double hips_margin =
      a.elbow_bend_deg >= p.front_hips_margin_min_bend_deg ? p.front_between_hips_margin * t.height : 0.0;
  a.wrist_between_hips = W.x > std::min(t.left_hip.x, t.right_hip.x) - hips_margin &&
                         W.x < std::max(t.left_hip.x, t.right_hip.x) + hips_margin;
  const bool hanging = straight && below_centre && !(p.front_wrist_between_hips && a.wrist_between_hips);
  // The paper's Alg. 1 takes a hand beside the user's box for an arm out: a straight arm on its way out (or down
  // and away) is out once its hand leaves the box, a little nearer down than an arm judged without the box.
  a.hand_beside_box = user_box && !user_box->contains(a.hand);
  const bool out_of_box = a.hand_beside_box && a.from_down_deg >= p.out_beside_box_min_from_down_deg;
  const bool raised = above_shoulders && a.straightness >= p.out_raised_min_straightness;
  if (!above_shoulders && a.hand.y > t.cut_below_y)
    a.pose = ArmPose::Unseen;  // the body cut above the hips and this hand at the edge: where it ends is unseen
  else if (raised || (straight && (a.from_down_deg >= p.out_min_from_down_deg || out_of_box)))
    a.pose = ArmPose::Out;  // stretched out: up, sideways, or down and away from the body
  else if (t.hips_seen && in_span && !above_shoulders && !below_hips && !at_face && !hanging &&
           (a.hand.y <= t.body_centre.y || a.hand.y > t.low_from_y))
    a.pose = a.hand.y > t.body_centre.y ? ArmPose::FrontLow : ArmPose::FrontHigh;  // as the vector will say
  else if (hanging || below_hips || (below_centre && a.from_down_deg <= p.rest_max_from_down_deg))
    a.pose = ArmPose::Rest;  // hanging, or the hand down by the hips
  else
    a.pose = ArmPose::Other;  // at the face, on the head, a bent arm raised
  return a;
}

bool commands(ArmPose a) { return a == ArmPose::Out || a == ArmPose::FrontHigh || a == ArmPose::FrontLow; }

}  // namespace

const char* arm_pose_name(ArmPose a) {
  switch (a) {
    case ArmPose::Unseen: return "UNSEEN";
    case ArmPose::Rest: return "REST";
    case ArmPose::Out: return "OUT";
    case ArmPose::FrontHigh: return "FRONT_HIGH";
    case ArmPose::FrontLow: return "FRONT_LOW";
    case ArmPose::Other: return "OTHER";
  }
  return "?";
}

std::string describe_pose_gesture(const PoseGesture& g) {
  const auto arm = [](const char* side, const ArmReading& a) {
    char text[128];
    if (a.pose == ArmPose::Unseen)
      std::snprintf(text, sizeof text, "%s %s", side, arm_pose_name(a.pose));
    else
      std::snprintf(text, sizeof text, "%s %s (s %.2f, %.0f deg, elbow %.0f deg%s%s)", side, arm_pose_name(a.pose),
                    a.straightness, a.from_down_deg, a.elbow_bend_deg, a.wrist_between_hips ? ", between the hips" : "", a.hand_beside_box ? ", beside the box" : "");
    return std::string(text);
  };
  return std::string(g.rule) + "; " + arm("left", g.left) + ", " + arm("right", g.right);
}

PoseGesture read_pose_gesture(const PoseLandmarks& lm, const PoseGestureParams& p, const std::optional<cv::Rect2f>& user_box,
                              const std::optional<cv::Size>& frame) {
  PoseGesture g;
  for (const PoseLandmark& l : lm)
    if (!(std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z) && std::isfinite(l.visibility))) {
      g.rule = "a landmark is not finite";
      return g;
    }
  const Torso t = torso_of(lm, p, user_box, frame);
  g.shoulder_centre = t.shoulder_mid;
  g.body_centre = t.body_centre;
  // The shoulders are what every arm is read from. The hips may be below the frame (the drone high and close):
  // BlazePose still places them, which is enough for an arm out or at rest, but a hand in front is judged
  // against p_bc and the hip line only when the hips are seen.
  g.torso_seen = seen(lm, L::kLeftShoulder, p.min_visibility) && seen(lm, L::kRightShoulder, p.min_visibility);
  if (!g.torso_seen) {
    g.rule = "shoulders not seen";
    return g;
  }
  g.left = read_arm(lm, t, p, user_box, L::kLeftShoulder, L::kLeftElbow, L::kLeftWrist, L::kLeftPinky, L::kLeftIndex);
  g.right = read_arm(lm, t, p, user_box, L::kRightShoulder, L::kRightElbow, L::kRightWrist, L::kRightPinky, L::kRightIndex);
  // The paper's gestures are made with one arm while the other does not command: two arms that both command (a
  // T-pose, arms crossed on the chest, one out and one in front) are no command, unless both are out and one
  // reaches out_dominant_reach times further than the other. A hand at the face or on the head
  // or a bent arm raised (OTHER) commands nothing itself and does not stop the other arm's gesture.
  bool left_commands = commands(g.left.pose), right_commands = commands(g.right.pose);
  if (left_commands && right_commands && g.left.pose == ArmPose::Out && g.right.pose == ArmPose::Out && p.out_dominant_reach > 0) {
    if (g.left.reach >= p.out_dominant_reach * g.right.reach) right_commands = false;
    if (g.right.reach >= p.out_dominant_reach * g.left.reach) left_commands = false;
  }
  if (left_commands && right_commands) {
    g.rule = "both arms command";
    return g;
  }
  if (!left_commands && !right_commands) {
    g.rule = "no arm commands";
    return g;
  }
  const ArmReading& arm = left_commands ? g.left : g.right;
  g.hand = arm.hand;
  if (arm.pose == ArmPose::Out) {
    g.kind = HandKind::Out;
    g.vector = arm.hand - g.shoulder_centre;
    g.rule = g.left.pose == g.right.pose ? "one arm out, reaching further than the other" : "one arm out";
  } else {
    g.kind = HandKind::Front;
    g.vector = arm.hand - g.body_centre;
    g.rule = "one hand in front";
  }
  return g;
}

}  // namespace gpilot
