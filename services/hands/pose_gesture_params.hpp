// Parameters of the paper's observation read from body landmarks (section `hands.pose_gesture`): when an arm is
// stretched out, in front of the body, or at rest. None of these is the paper's (it reads skin); straightness,
// the torso's span and the face are the limits of the keypoint rules the real development set is labelled with
// (tools/eval_hands/keypoint_truth).
#pragma once

#include "config_schema.hpp"

namespace gpilot {

struct PoseGestureParams {
  double min_visibility = 0.5;        //!< an arm's shoulder, elbow and wrist need at least this visibility to be read
  double out_min_straightness = 0.85; //!< OUT: |W-S| / (|S-E| + |E-W|) at least this (a straight arm)
  double out_min_from_down_deg = 25;  //!< OUT below the shoulders: the arm at least this far from straight down with
                                      //!< the wrist beside the torso (the paper's DOWN arm points about 30 deg from
                                      //!< down; a straight arm nearer down hangs at rest)
  double rest_max_from_down_deg = 45; //!< REST: a bent arm whose hand is below the body centre, at most this far from
                                      //!< straight down, rests (a hand on the hip)
  double front_min_depth = 0.6;       //!< FRONT: a straight arm hanging in the torso's span is a hand in front of the
                                      //!< body when its wrist is this many shoulder widths nearer the camera than its
                                      //!< shoulder (BlazePose's z)
  double span_margin = 0.1;           //!< the torso's span in x is its shoulders' and hips' extent grown by this many
                                      //!< torso heights each side
  double face_radius = 0.4;           //!< a wrist within this many shoulder widths of the face's centre (nose, eyes,
                                      //!< ears) is at the face: no command (a hand at the face is not the front gesture)
  double hand_beyond_wrist = 0.5;     //!< the hand's point: from the wrist this share of the way to the knuckles'
                                      //!< midpoint (index, pinky), where the paper's skin blob is centred

  template <class V>
  void visit(V& v) {
    v("min_visibility", min_visibility, 0.0, 1.0, "an arm is read when its shoulder, elbow and wrist are at least this visible");
    v("out_min_straightness", out_min_straightness, 0.0, 1.0, "OUT: |wrist-shoulder| / (upper arm + forearm) at least this");
    v("out_min_from_down_deg", out_min_from_down_deg, 0.0, 180.0, "OUT below the shoulders: at least this far from straight down, the wrist beside the torso");
    v("rest_max_from_down_deg", rest_max_from_down_deg, 0.0, 180.0, "REST: a bent arm with the hand below the body centre, at most this far from down");
    v("front_min_depth", front_min_depth, 0.0, 10.0, "FRONT: a hanging arm's wrist this many shoulder widths nearer the camera than its shoulder");
    v("span_margin", span_margin, 0.0, 1.0, "torso span in x: shoulders' and hips' extent grown by this many torso heights");
    v("face_radius", face_radius, 0.0, 2.0, "a wrist within this many shoulder widths of the face centre is at the face (no command)");
    v("hand_beyond_wrist", hand_beyond_wrist, 0.0, 1.5, "hand point: this share of the way from the wrist to the knuckles");
  }
};

}  // namespace gpilot
