// Gesture truth from 2-D body keypoints (COCO names), per arm and per person: fixed geometric rules, printed
// by gpilot-eval-hands --help (keypoint_truth_rules()). Image pixels, y down; left/right are the PERSON's own.
// Pure: no images, no COCO file, no clock.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace gpilot {

enum class ArmTruth { Out = 0, Rest, FrontHigh, FrontLow, Ambiguous };
enum class PersonTruth { Out = 0, Front, Rest, Ambiguous };
constexpr int kArmTruths = 5, kPersonTruths = 4;

const char* arm_truth_name(ArmTruth t);        // OUT, REST, FRONT_HIGH, FRONT_LOW, AMBIGUOUS
const char* person_truth_name(PersonTruth t);  // OUT, FRONT, REST, AMBIGUOUS
bool is_front(ArmTruth t);

// The fixed limits of the rules.
struct KeypointTruthLimits {
  static constexpr double kStraight = 0.85;          //!< straightness at or above: a straight arm
  static constexpr double kOutFromDownDeg = 45.0;    //!< OUT: at least this far from straight down
  static constexpr double kSpanMarginTorso = 0.1;    //!< torso span margin, torso heights
  static constexpr double kFaceGrow = 0.2;           //!< "at the face": each side of the face box moved out by this x its size
};

struct BodyPoint {
  cv::Point2f p;
  int v = 0;  //!< COCO visibility: 0 not labelled, 1 labelled hidden, 2 visible
};

// The keypoints the rules read (COCO names in the comments).
struct BodyKeypoints {
  BodyPoint nose, left_eye, right_eye, left_ear, right_ear;        // nose, left_eye, ... right_ear
  BodyPoint left_shoulder, right_shoulder, left_elbow, right_elbow;  // left_shoulder, ...
  BodyPoint left_wrist, right_wrist, left_hip, right_hip;           // left_wrist, ..., right_hip

  // Fills every point through lookup(COCO keypoint name); a name lookup does not know stays v = 0.
  static BodyKeypoints from(const std::function<std::optional<BodyPoint>(const std::string&)>& lookup);
};

// One arm's measurements and label.
struct ArmKeypointTruth {
  ArmTruth label = ArmTruth::Ambiguous;
  const char* reason = "";
  cv::Point2f shoulder, elbow, wrist;
  double straightness = 0;          //!< |W-S| / (|S-E| + |E-W|)
  double angle_from_down_deg = 0;   //!< angle between W-S and image-down, 0..180
  bool wrist_above_shoulder_line = false;
  bool wrist_below_hip_line = false;
  bool wrist_below_torso_centre = false;
  bool wrist_in_torso_span = false;  //!< x only: within the torso span (the shared set's field of that name
                                     //!< also needs the wrist between the shoulder and hip lines)
  bool wrist_at_face = false;
};

struct PersonKeypointTruth {
  bool usable = false;        //!< false: a shoulder, elbow, wrist or hip has v < 2 (skip_reason names it)
  std::string skip_reason;
  ArmKeypointTruth left, right;
  PersonTruth person = PersonTruth::Ambiguous;
  cv::Point2f shoulder_mid, hip_mid, torso_centre;
  double torso_height = 0;    //!< |shoulder midpoint - hip midpoint|
  double span_min_x = 0, span_max_x = 0;  //!< torso span with its margin
  std::optional<cv::Rect2f> face_box;     //!< from nose/eyes/ears (v >= 1), not grown; none if none labelled
};

// The rules (see keypoint_truth_rules()).
PersonKeypointTruth keypoint_truth(const BodyKeypoints& k);

// Face box from the labelled (v >= 1) nose/eyes/ears, as ../shared/data/real_people/README.md makes its
// face_box: width = max(1.15 x their x-extent, 0.45 x shoulder width (|x difference| of the shoulders)),
// height = 1.3 x width, centred on the middle of their x-extent and 0.1 x height below their mean y.
// None if no face point is labelled.
std::optional<cv::Rect2f> keypoint_face_box(const BodyKeypoints& k);

// Person from arms: OUT if any arm OUT; else FRONT if any arm FRONT; REST if both REST; else AMBIGUOUS.
PersonTruth person_truth(ArmTruth left, ArmTruth right);

// The rules as text for --help.
std::string keypoint_truth_rules();

}  // namespace gpilot
