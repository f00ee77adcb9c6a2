// Parameters of the paper's observation read from body landmarks (section `hands.pose_gesture`): when an arm is
// stretched out, in front of the body, or at rest. None of these is the paper's (it reads skin); straightness,
// the torso's span and the face are the limits of the keypoint rules the real development set is labelled with
// (tools/eval_hands/keypoint_truth).
#pragma once

#include "config_schema.hpp"

namespace gpilot {

struct PoseGestureParams {
  double min_visibility = 0.5;        //!< an arm's shoulder, elbow and wrist need at least this visibility to be read
  double out_min_straightness = 0.75; //!< OUT: |W-S| / (|S-E| + |E-W|) at least this (a straight arm: the model's
                                      //!< landmarks of a straight arm measure less straight than the hand-drawn
                                      //!< keypoints, whose truth takes 0.85)
  double out_raised_min_straightness = 0.7; //!< OUT with the wrist above the shoulders: at least this straight (a raised
                                          //!< arm's landmarks bend more than its pose; a hand on the head is ~0.5)
  double out_min_from_down_deg = 40;  //!< OUT below the shoulders: a straight arm at least this far from straight down
                                      //!< (a straight arm nearer down hangs at rest, as the real photos' keypoint
                                      //!< truth has it; DOWN is the arm out and down, 40..63 deg with decide's lambda4)
  double out_beside_box_min_from_down_deg = 25; //!< OUT: a straight arm at least this far from down whose hand is
                                                //!< outside the user box (the paper's Alg. 1: a hand beside the body
                                                //!< box is out); 180: the box is not used
  double out_dominant_reach = 1.5;    //!< both arms OUT: the one whose wrist reaches this many times further from its
                                      //!< shoulder commands alone (BlazePose may place an arm hanging unseen, dark on
                                      //!< a dark wall, out and bent beside the body); reaches nearer alike (a T-pose)
                                      //!< are no command. 0: both OUT are always no command
  double rest_max_from_down_deg = 45; //!< REST: a bent arm whose hand is below the body centre, at most this far from
                                      //!< straight down, rests (a hand on the hip)
  bool front_wrist_between_hips = true; //!< FRONT: a straight arm whose wrist lies between the hips in x is held in
                                        //!< front of the body, not hanging (the hand low in front, seen from ahead)
  double front_between_hips_margin = 0.1; //!< ... between the hip joints grown by this many torso heights each side
                                          //!< when the elbow bends (a hanging arm's wrist is beside the thigh, a
                                          //!< hip joint's width outside it; a hand held low in front, the forearm
                                          //!< turned in to the belly, may sit at the joint's x)
  double front_hips_margin_min_bend_deg = 30; //!< ... bends: upper arm to forearm at least this in the image (e2e:
                                              //!< a hand low in front 37-73 deg, a hanging arm 0-17 deg)
  double hips_min_visibility = 0.4;   //!< FRONT is judged only with both hips at least this visible (the hip line and
                                      //!< p_bc measured); lower than min_visibility: hips in the frame's bottom 40 px
                                      //!< (the drone above the user) reach it on 79 % of e2e frames (0.5: 66 %),
                                      //!< hips below the frame on 6.8 % (0.5: 1.6 %)
  double hips_min_frame_margin = 0.1; //!< ... and both hips at least this many torso heights above the frame's bottom
                                      //!< edge (0: on it is enough)
  double low_hips_min_frame_margin = 0.6; //!< hips within this many torso heights of the frame's bottom edge may
                                          //!< be a body cut below them: placed inside the frame, visible, too high
  double low_hips_doubt = 0.5;        //!< ... by up to this many torso heights (e2e: 0.54 for hips 7 px below the
                                      //!< frame, at visibility 0.9), which raises p_bc by half that: a hand in
                                      //!< front below p_bc by less than half of it is not judged (a hand read
                                      //!< higher than p_bc stays higher whatever the hips' error)
  double cut_hand_margin = 0.25;      //!< the hips not seen (the body cut above them): an arm whose hand lies below
                                      //!< the shoulders and within this many user-box widths (0.25: a hand square)
                                      //!< of the frame's bottom edge is not read (e2e: a hanging hand out of view
                                      //!< placed 0-1.6 hand squares inside the frame, read as out and down; true
                                      //!< arms out there 2.1-2.6)
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
    v("out_raised_min_straightness", out_raised_min_straightness, 0.0, 1.0, "OUT with the wrist above the shoulders: straightness at least this");
    v("out_min_from_down_deg", out_min_from_down_deg, 0.0, 180.0, "OUT below the shoulders: a straight arm at least this far from straight down");
    v("out_beside_box_min_from_down_deg", out_beside_box_min_from_down_deg, 0.0, 180.0, "OUT: a straight arm this far from down with the hand outside the user box (180: box not used)");
    v("out_dominant_reach", out_dominant_reach, 0.0, 10.0, "both arms OUT: the one reaching this many times further from its shoulder commands alone (0: off)");
    v("rest_max_from_down_deg", rest_max_from_down_deg, 0.0, 180.0, "REST: a bent arm with the hand below the body centre, at most this far from down");
    v("front_wrist_between_hips", front_wrist_between_hips, "FRONT: a straight arm with the wrist between the hips in x is in front of the body, not hanging");
    v("front_between_hips_margin", front_between_hips_margin, 0.0, 1.0, "FRONT: the hips' extent in x the wrist is between, grown by this many torso heights each side for a bent arm");
    v("front_hips_margin_min_bend_deg", front_hips_margin_min_bend_deg, 0.0, 180.0, "FRONT: the hips' margin applies to an arm bent at the elbow at least this much");
    v("hips_min_visibility", hips_min_visibility, 0.0, 1.0, "FRONT is judged only with both hips at least this visible");
    v("hips_min_frame_margin", hips_min_frame_margin, 0.0, 2.0, "FRONT is judged only with both hips at least this many torso heights above the frame's bottom edge");
    v("low_hips_min_frame_margin", low_hips_min_frame_margin, 0.0, 2.0, "hips within this many torso heights of the frame's bottom edge may be placed too high");
    v("low_hips_doubt", low_hips_doubt, 0.0, 2.0, "... by up to this many torso heights: a hand in front below p_bc by less than half of it is not judged");
    v("cut_hand_margin", cut_hand_margin, 0.0, 2.0, "hips not seen: an arm whose hand is below the shoulders and within this many box widths of the frame's bottom edge is not read");
    v("span_margin", span_margin, 0.0, 1.0, "torso span in x: shoulders' and hips' extent grown by this many torso heights");
    v("face_radius", face_radius, 0.0, 2.0, "a wrist within this many shoulder widths of the face centre is at the face (no command)");
    v("hand_beyond_wrist", hand_beyond_wrist, 0.0, 1.5, "hand point: this share of the way from the wrist to the knuckles");
  }
};

}  // namespace gpilot
