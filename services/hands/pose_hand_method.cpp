#include "hands/pose_hand_method.hpp"

#include <cmath>
#include <utility>

#include "hand_square.hpp"
#include "hands/pose_gesture.hpp"

namespace gpilot {

PoseHandMethod::PoseHandMethod(const HandsParams& params, PoseModels models)
    : params_(params), pose_(params.pose, std::move(models)) {}

void PoseHandMethod::reset() {
  pose_.reset();
  track_id_ = -1;
}

std::string PoseHandMethod::description() const {
  return "pose model " + pose_landmark_path(params_.pose) + ", detector " + pose_detector_path(params_.pose);
}

HandsOutput PoseHandMethod::observe(const cv::Mat& bgr, const UserView& user, int64_t utime) {
  HandsOutput out;
  out.user_box = user.box;
  // Without a pose the paper's reference points of the box (the skin method's) are published, so HAND_OBS
  // always says where p_uc and p_bc are.
  const HandGeometry box_geometry = hand_geometry(params_, user.box, bgr.size());
  out.shoulder_centre = box_geometry.shoulder_centre;
  out.body_centre = box_geometry.body_centre;
  if (user.track_id != track_id_) {
    pose_.reset();  // a new user: nothing of the last one's body carries over
    track_id_ = user.track_id;
  }
  if (!user.tracking) return out;

  const PoseResult r = pose_.estimate(bgr, user.box, utime);
  if (r.nonfinite) {
    // A net that computes NaN or Inf (a damaged model file, a numeric fault) says nothing about the user: the
    // frame is refused (a counted rejection in HEALTH, no HAND_OBS), never read as a pose.
    out.refused = "the pose model gave a non-finite output (NaN/Inf): no observation";
    return out;
  }
  PoseDiagnostics diagnostics;
  diagnostics.score = r.pose_flag;
  if (!r.found) {
    out.pose = diagnostics;
    return out;
  }
  diagnostics.landmarks = r.landmarks;
  out.pose = diagnostics;
  const PoseGesture g = read_pose_gesture(r.landmarks, params_.pose_gesture, user.box, bgr.size());
  out.pose->reading = describe_pose_gesture(g);
  if (!g.torso_seen) return out;
  out.shoulder_centre = g.shoulder_centre;
  out.body_centre = g.body_centre;
  out.kind = g.kind;
  if (g.kind == HandKind::None) return out;
  out.vector = g.vector;
  out.hand = g.hand;
  // The paper's hand square (w/4 of the user box) around the hand, for the picture; clipped to the frame.
  const int side = hand_square_side(params_.hand_square_ratio, user.box.width, bgr.size());
  out.hand_box = cv::Rect(static_cast<int>(std::lround(g.hand.x)) - side / 2, static_cast<int>(std::lround(g.hand.y)) - side / 2,
                          side, side) & cv::Rect(0, 0, bgr.cols, bgr.rows);
  return out;
}

}  // namespace gpilot
