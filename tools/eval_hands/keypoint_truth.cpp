#include "keypoint_truth.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gpilot {

namespace {

using L = KeypointTruthLimits;

double dist(cv::Point2f a, cv::Point2f b) { return std::hypot(static_cast<double>(a.x - b.x), static_cast<double>(a.y - b.y)); }

// y of the line through a and b at x (a vertical line: the mean y).
double line_y_at(cv::Point2f a, cv::Point2f b, double x) {
  const double dx = static_cast<double>(b.x) - a.x;
  if (std::abs(dx) < 1e-6) return (static_cast<double>(a.y) + b.y) / 2;
  return a.y + (x - a.x) * (static_cast<double>(b.y) - a.y) / dx;
}

cv::Point2f mid(cv::Point2f a, cv::Point2f b) { return (a + b) * 0.5f; }

ArmKeypointTruth arm_truth(const BodyKeypoints& k, const PersonKeypointTruth& t, const BodyPoint& S, const BodyPoint& E,
                           const BodyPoint& W) {
  ArmKeypointTruth a;
  a.shoulder = S.p;
  a.elbow = E.p;
  a.wrist = W.p;
  const double path = dist(S.p, E.p) + dist(E.p, W.p);
  a.straightness = path > 0 ? dist(S.p, W.p) / path : 0.0;
  const double dx = static_cast<double>(W.p.x) - S.p.x, dy = static_cast<double>(W.p.y) - S.p.y;
  a.angle_from_down_deg = (dx == 0 && dy == 0) ? 0.0 : std::abs(std::atan2(dx, dy)) * 180.0 / M_PI;
  const double wx = W.p.x, wy = W.p.y;
  const double shoulder_y = line_y_at(k.left_shoulder.p, k.right_shoulder.p, wx);
  const double hip_y = line_y_at(k.left_hip.p, k.right_hip.p, wx);
  a.wrist_above_shoulder_line = wy < shoulder_y;
  a.wrist_below_hip_line = wy > hip_y;
  a.wrist_below_torso_centre = wy > t.torso_centre.y;
  a.wrist_in_torso_span = wx >= t.span_min_x && wx <= t.span_max_x;
  if (t.face_box) {
    const cv::Rect2f f = *t.face_box;
    const float gw = f.width * static_cast<float>(L::kFaceGrow), gh = f.height * static_cast<float>(L::kFaceGrow);
    const cv::Rect2f g(f.x - gw, f.y - gh, f.width + 2 * gw, f.height + 2 * gh);
    a.wrist_at_face = wx >= g.x && wx <= g.x + g.width && wy >= g.y && wy <= g.y + g.height;
  }
  const bool straight = a.straightness >= L::kStraight;
  const bool between_lines = !a.wrist_above_shoulder_line && !a.wrist_below_hip_line;
  if (straight && (a.angle_from_down_deg >= L::kOutFromDownDeg || a.wrist_above_shoulder_line)) {
    a.label = ArmTruth::Out;
    a.reason = a.angle_from_down_deg >= L::kOutFromDownDeg ? "straight, >= 45 deg from down" : "straight, wrist above shoulder line";
  } else if (straight && a.wrist_below_torso_centre) {
    a.label = ArmTruth::Rest;
    a.reason = "straight arm hanging";
  } else if (a.wrist_in_torso_span && between_lines && !a.wrist_at_face) {
    a.label = a.wrist_below_torso_centre ? ArmTruth::FrontLow : ArmTruth::FrontHigh;
    a.reason = "wrist over torso";
  } else if (a.wrist_below_hip_line) {
    a.label = ArmTruth::Rest;
    a.reason = "wrist below hip line";
  } else {
    a.label = ArmTruth::Ambiguous;
    a.reason = a.wrist_at_face ? "wrist at the face" : "no rule";
  }
  return a;
}

}  // namespace

const char* arm_truth_name(ArmTruth t) {
  switch (t) {
    case ArmTruth::Out: return "OUT";
    case ArmTruth::Rest: return "REST";
    case ArmTruth::FrontHigh: return "FRONT_HIGH";
    case ArmTruth::FrontLow: return "FRONT_LOW";
    case ArmTruth::Ambiguous: return "AMBIGUOUS";
  }
  return "?";
}

const char* person_truth_name(PersonTruth t) {
  switch (t) {
    case PersonTruth::Out: return "OUT";
    case PersonTruth::Front: return "FRONT";
    case PersonTruth::Rest: return "REST";
    case PersonTruth::Ambiguous: return "AMBIGUOUS";
  }
  return "?";
}

bool is_front(ArmTruth t) { return t == ArmTruth::FrontHigh || t == ArmTruth::FrontLow; }

BodyKeypoints BodyKeypoints::from(const std::function<std::optional<BodyPoint>(const std::string&)>& lookup) {
  BodyKeypoints k;
  const std::pair<const char*, BodyPoint*> names[] = {
      {"nose", &k.nose},
      {"left_eye", &k.left_eye},
      {"right_eye", &k.right_eye},
      {"left_ear", &k.left_ear},
      {"right_ear", &k.right_ear},
      {"left_shoulder", &k.left_shoulder},
      {"right_shoulder", &k.right_shoulder},
      {"left_elbow", &k.left_elbow},
      {"right_elbow", &k.right_elbow},
      {"left_wrist", &k.left_wrist},
      {"right_wrist", &k.right_wrist},
      {"left_hip", &k.left_hip},
      {"right_hip", &k.right_hip},
  };
  for (const auto& [name, point] : names)
    if (const auto p = lookup(name)) *point = *p;
  return k;
}

std::optional<cv::Rect2f> keypoint_face_box(const BodyKeypoints& k) {
  std::vector<cv::Point2f> pts;
  for (const BodyPoint* p : {&k.nose, &k.left_eye, &k.right_eye, &k.left_ear, &k.right_ear})
    if (p->v >= 1) pts.push_back(p->p);
  if (pts.empty()) return std::nullopt;
  double min_x = pts[0].x, max_x = pts[0].x, sum_y = 0;
  for (const auto& p : pts) {
    min_x = std::min(min_x, static_cast<double>(p.x));
    max_x = std::max(max_x, static_cast<double>(p.x));
    sum_y += p.y;
  }
  const double shoulder_width = std::abs(static_cast<double>(k.left_shoulder.p.x) - k.right_shoulder.p.x);
  const double w = std::max(1.15 * (max_x - min_x), 0.45 * shoulder_width);
  const double h = 1.3 * w;
  const double cx = (min_x + max_x) / 2, cy = sum_y / static_cast<double>(pts.size()) + 0.1 * h;
  return cv::Rect2f(static_cast<float>(cx - w / 2), static_cast<float>(cy - h / 2), static_cast<float>(w), static_cast<float>(h));
}

PersonTruth person_truth(ArmTruth left, ArmTruth right) {
  // The paper's gestures are made with one arm: two arms that both command (both out, both in front, one of
  // each) are none of its gestures.
  const auto commands = [](ArmTruth a) { return a == ArmTruth::Out || is_front(a); };
  if (commands(left) && commands(right)) return PersonTruth::Ambiguous;
  if (left == ArmTruth::Out || right == ArmTruth::Out) return PersonTruth::Out;
  if (is_front(left) || is_front(right)) return PersonTruth::Front;
  if (left == ArmTruth::Rest && right == ArmTruth::Rest) return PersonTruth::Rest;
  return PersonTruth::Ambiguous;
}

PersonKeypointTruth keypoint_truth(const BodyKeypoints& k) {
  PersonKeypointTruth t;
  const std::pair<const char*, const BodyPoint*> needed[] = {
      {"left_shoulder", &k.left_shoulder}, {"right_shoulder", &k.right_shoulder}, {"left_elbow", &k.left_elbow},
      {"right_elbow", &k.right_elbow},     {"left_wrist", &k.left_wrist},         {"right_wrist", &k.right_wrist},
      {"left_hip", &k.left_hip},           {"right_hip", &k.right_hip},
  };
  for (const auto& [name, p] : needed)
    if (p->v < 2) {
      t.skip_reason += (t.skip_reason.empty() ? "" : ", ") + std::string(name) + " v=" + std::to_string(p->v);
    }
  if (!t.skip_reason.empty()) {
    t.skip_reason = "not visible (v < 2): " + t.skip_reason;
    return t;
  }
  t.usable = true;
  t.shoulder_mid = mid(k.left_shoulder.p, k.right_shoulder.p);
  t.hip_mid = mid(k.left_hip.p, k.right_hip.p);
  t.torso_centre = mid(t.shoulder_mid, t.hip_mid);
  t.torso_height = dist(t.shoulder_mid, t.hip_mid);
  const float xs[] = {k.left_shoulder.p.x, k.right_shoulder.p.x, k.left_hip.p.x, k.right_hip.p.x};
  const double margin = L::kSpanMarginTorso * t.torso_height;
  t.span_min_x = *std::min_element(std::begin(xs), std::end(xs)) - margin;
  t.span_max_x = *std::max_element(std::begin(xs), std::end(xs)) + margin;
  t.face_box = keypoint_face_box(k);
  t.left = arm_truth(k, t, k.left_shoulder, k.left_elbow, k.left_wrist);
  t.right = arm_truth(k, t, k.right_shoulder, k.right_elbow, k.right_wrist);
  t.person = person_truth(t.left.label, t.right.label);
  return t;
}

std::string keypoint_truth_rules() {
  return "Truth from the COCO keypoints, per arm (image pixels, y down; left/right are the person's own; S, E, W =\n"
         "shoulder, elbow, wrist of the arm):\n"
         "  straightness s = |W-S| / (|S-E| + |E-W|); angle from down = angle between W-S and image-down.\n"
         "  shoulder line / hip line: the lines through the two shoulders / two hips, evaluated at W's x.\n"
         "  torso centre = midpoint of the shoulder midpoint and the hip midpoint; torso height = their distance;\n"
         "  torso span = min..max x of shoulders and hips, +- 0.1 torso height.\n"
         "  face box: from nose/eyes/ears (width max(1.15 x their x-extent, 0.45 x shoulder width in x), height 1.3 x\n"
         "  width, centred on their x-extent, 0.1 height below their mean y); 'at the face' = W in it grown by 20 %\n"
         "  (each side moved out by 0.2 of the box's width / height, as ../shared/data/real_people's labels).\n"
         "  First match wins:\n"
         "  1. OUT:   s >= 0.85 and (angle from down >= 45 deg or W above the shoulder line).\n"
         "  2. REST:  s >= 0.85, < 45 deg from down and W below the torso centre (straight arm hanging).\n"
         "  3. FRONT: W within the torso span, between shoulder and hip line, not at the face;\n"
         "            FRONT_HIGH if W is above the torso centre, else FRONT_LOW.\n"
         "  4. REST:  W below the hip line.\n"
         "  5. AMBIGUOUS: anything else (reported, not scored).\n"
         "  Annotations with v < 2 on a shoulder, elbow, wrist or hip are skipped (counted).\n"
         "Per person: AMBIGUOUS if both arms are OUT or FRONT (the paper's gestures are one-armed); else OUT if an arm\n"
         "is OUT; FRONT if an arm is FRONT; REST if both arms REST; else AMBIGUOUS.\n"
         "Expected stage kind: OUT -> OUT, FRONT -> FRONT, REST -> NONE.\n";
}

}  // namespace gpilot
