// Parameters of gpilot-hands (section `hands`): the method (pose or the paper's skin), the body-pose model and
// the rules that read the paper's gestures from it, and for skin: the skin model, search rectangle, Alg. 1 and 2.
#pragma once

#include <string>

#include "config_schema.hpp"
#include "hands/pose_gesture_params.hpp"
#include "pose/pose_params.hpp"

namespace gpilot {

// The skin model that learns the user and the scene (SkinAdapter): none of these is the paper's (its future work).
struct SkinAdaptParams {
  bool enabled = true;               //!< false: the trained table alone (the paper)
  double user_weight = 0.5;          //!< a: weight of this user's skin histogram added to the table's P(c|skin)
  double user_rate = 0.3;            //!< each new face blends in at this rate
  double table_share = 1.0;          //!< share of the table's P(c|skin) kept once a user is learnt (1: the user
                                     //!< only adds colours; lower: colours unlike the user's face lose weight)
  double scene_weight = 0.6;         //!< b: share of the scene histogram in P(c|not skin)
  double scene_rate = 0.1;           //!< each frame's scene sample blends in at this rate (decay)
  int scene_stride = 4;              //!< the scene is sampled every N-th pixel in x and y
  double scene_margin = 1.2;         //!< the scene is the frame outside the user box grown by this many box widths
                                     //!< (a stretched-out hand there is a small share of the scene's colours)
  // The user's clothing (the torso of the box): a shirt the table calls skin (orange, peach, pink) is not skin.
  double clothing_weight = 0.2;      //!< c: share of the torso's colour histogram in P(c|not skin) (0 = off)
  double clothing_rate = 0.1;        //!< each frame's torso sample blends in at this rate (decay)
  double clothing_user_level = 0.0001; //!< torso pixels of the user's skin colours are not clothing: a colour whose
                                     //!< (smoothed) face histogram is at least this fraction of its peak (a hand in front)
  // The cheek band of the Haar face box: below the eyes, inside the face outline, above the chin.
  double face_band_top = 0.5;        //!< band top, fraction of the face box height
  double face_band_bottom = 0.85;    //!< band bottom, fraction of the face box height
  double face_band_side = 0.2;       //!< band inset from each side, fraction of the face box width
  double face_min_prior = 0.3;       //!< face pixels the table gives P(skin) above this are learnt (not eyes, hair)
  int min_face_samples = 50;         //!< a face with fewer such pixels teaches nothing
  int min_scene_samples = 200;       //!< a scene sample with fewer pixels teaches nothing
  int rebuild_frames = 5;            //!< the adapted table is rebuilt at most this often, frames (first state at once)
  double smoothing_sigma = 1.0;      //!< Gaussian blur of the learnt histograms, bins

  template <class V>
  void visit(V& v) {
    v("enabled", enabled, "learn the user's skin (face) and the scene's colours on top of the trained table");
    v("user_weight", user_weight, 0.0, 1.0, "weight of the user's face histogram added to P(colour|skin)");
    v("user_rate", user_rate, 0.0, 1.0, "blend rate of each new face sample");
    v("table_share", table_share, 0.0, 1.0, "share of the table's P(colour|skin) kept once a user is learnt");
    v("scene_weight", scene_weight, 0.0, 1.0, "share of the scene histogram in P(colour|not skin)");
    v("scene_rate", scene_rate, 0.0, 1.0, "blend rate of each frame's scene sample (decay)");
    v("scene_stride", scene_stride, 1, 64, "scene sampled every N-th pixel in x and y");
    v("scene_margin", scene_margin, 0.0, 10.0, "scene = frame outside the user box grown by this many box widths");
    v("clothing_weight", clothing_weight, 0.0, 1.0, "share of the user's torso colours in P(colour|not skin) (0 = off)");
    v("clothing_rate", clothing_rate, 0.0, 1.0, "blend rate of each frame's torso sample (decay)");
    v("clothing_user_level", clothing_user_level, 0.0, 1.0, "torso colours at this fraction of the face histogram's peak are the user's skin, not clothing");
    v("face_band_top", face_band_top, 0.0, 1.0, "cheek band top, fraction of face box height");
    v("face_band_bottom", face_band_bottom, 0.0, 1.0, "cheek band bottom, fraction of face box height");
    v("face_band_side", face_band_side, 0.0, 0.5, "cheek band inset each side, fraction of face box width");
    v("face_min_prior", face_min_prior, 0.0, 1.0, "face pixels with table P(skin) above this are learnt");
    v("min_face_samples", min_face_samples, 1, 1000000, "a face with fewer learnable pixels is ignored");
    v("min_scene_samples", min_scene_samples, 1, 1000000, "a scene sample with fewer pixels is ignored");
    v("rebuild_frames", rebuild_frames, 1, 10000, "rebuild the adapted table at most every N frames");
    v("smoothing_sigma", smoothing_sigma, 0.0, 8.0, "Gaussian blur of the learnt histograms, bins");
  }
  void check(const ParamCheck& c) const {
    c.require(scene_weight + clothing_weight <= 1.0, "clothing_weight",
              "scene_weight + clothing_weight = " + ParamWriter::format_number(scene_weight + clothing_weight, false) +
                  " leaves the table's non-skin class a negative share (at most 1)");
    c.require(face_band_top < face_band_bottom, "face_band_top",
              ParamWriter::format_number(face_band_top, false) + " must be above (less than) face_band_bottom " +
                  ParamWriter::format_number(face_band_bottom, false));
  }
};

struct SkinParams {
  std::string model = "data/skin/skin_model.yaml";  //!< trained histogram model (gpilot-skin-train), relative to the project root
  // 0.75, not 0.5: background photographs have many colours the smoothed table puts at P 0.5..0.75 (building.jpg:
  // 8.4 % of its pixels at 0.5, 4.1 % at 0.75) while held-out skin F1 only drops from 0.900 to 0.876 (data/skin/README.md).
  double threshold = 0.75;          //!< P(skin | rgb) above this is skin
  // Not in the paper: a morphological opening (erode then dilate, square of side 2r+1) of the skin mask removes
  // the thin edges and specks a textured background leaves, which Alg. 1 would otherwise count outside the box.
  // r = round(open_radius_ratio x user box width): 2 px for an 85 px box, so a hand (w/4 wide) survives it.
  double open_radius_ratio = 0.025;  //!< opening radius / box width (0 = off)
  // Ours: a frame without colour (a monochrome or IR camera, a greyscale video) cannot show skin; the stage refuses
  // it with that reason (colour_check.hpp). Greyscale JPEGs have chroma 0-2; the palest colour photo of the real
  // development set has 9 % of its pixels at HSV saturation > 40.
  double min_colour_fraction = 0.005;  //!< a frame with fewer sampled pixels of min_chroma is colourless (0 = off)
  int min_chroma = 12;                 //!< max(B,G,R) - min(B,G,R) of a pixel that has colour
  SkinAdaptParams adapt;

  template <class V>
  void visit(V& v) {
    v("model", model, "skin model file from gpilot-skin-train (relative paths: from the project root)");
    v("threshold", threshold, 0.0, 1.0, "P(skin|colour) above this is skin");
    v("open_radius_ratio", open_radius_ratio, 0.0, 0.25, "skin mask opening radius / box width (0 = off; ours, not the paper's)");
    v("min_colour_fraction", min_colour_fraction, 0.0, 1.0, "frames with fewer sampled pixels of min_chroma are refused: no colour, no skin (0 = off; ours)");
    v("min_chroma", min_chroma, 1, 255, "max(B,G,R) - min(B,G,R) of a pixel that has colour");
    v.group("adapt", adapt);
  }
};

struct HandsParams {
  //! the hands method (hands_core_factory.hpp): skin, the paper's Alg. 1/2 on a skin table; pose, the user's body
  //! landmarks (BlazePose) read by pose_gesture
  std::string method = "pose";
  PoseParams pose;                  //!< the pose method's models, detector, tracking and smoothing
  PoseGestureParams pose_gesture;   //!< the pose method's rules: which arm commands, and how
  SkinParams skin;
  // Search rectangle: the user box extended sideways and up, so that a stretched-out arm is inside it.
  double roi_extend_side = 1.2;     //!< added on each side, in user box widths: an arm's reach (shoulder
                                    //!< 0.35 w from the centre, arm 1.3 w), so skin beyond it is not taken for a hand
  double roi_extend_top = 0.25;     //!< added above, in user box heights
  double roi_extend_bottom = 0.0;   //!< added below, in user box heights
  // Inside the user box, face/neck and legs/feet are removed by preset ratios of the box (the paper's numbers are not given).
  double face_remove_ratio = 0.2;   //!< top fraction of the box removed (face and neck)
  double legs_remove_ratio = 0.35;  //!< bottom fraction of the box removed (legs, feet, hands at rest): below the
                                    //!< hips, so a hand low in front of the body (FURTHER) stays in
  double neck_in_faces = 0.35;      //!< with the user's face known (USER_TRACK's, carried along with the box between
                                    //!< re-checks), this many face heights below it are neck, removed with the face
                                    //!< band whatever face_remove_ratio leaves (0 = the box's ratio alone; ours)
  double shoulder_centre_ratio = 0.2;  //!< p_uc sits this fraction of the box height below its top, centred
  double body_centre_ratio = 0.5;   //!< p_bc: the box centre (the paper)
  double hand_square_ratio = 0.25;  //!< hand square side = ratio × box width (paper w/4)
  int out_min_skin = 30;            //!< Alg. 1 runs only with more than this many skin pixels outside the box (paper 30)
  double lambda1 = 0.5;             //!< Alg. 1 weight of F_skin (paper λ1)
  double lambda2 = 0.2;             //!< Alg. 1 weight of the height above p_uc (paper λ2)
  double lambda3 = 0.013;           //!< Alg. 2 weight of F_skin (paper λ3)
  double front_gate_ratio = 0.2;    //!< Alg. 2 accepts |p_bc.x - p.x| < ratio × w (paper w/5)
  int front_min_skin = 30;          //!< Alg. 2 accepts F_skin above this (paper 30)
  double min_skin_square_share = 0.25;  //!< both need more than this share of the hand square's area where that is
                                        //!< less than the paper's 30 px: a far user's hand (8-10 m, an 8 px square)
                                        //!< shows 20-35 skin pixels, so 30 lost DOWN and CLOSER there (0 = off; ours)
  double down_min_skin_square_share = 0.15;  //!< Alg. 1 with its hand below the shoulder line: this share instead
                                             //!< (out_min_angle_deg leaves out the side of a far DOWN hand nearer
                                             //!< the body: 11-17 px counted at 9.8-9.9 m; 0 = as above; ours)
  int match_window = 15;            //!< frames/tracks wait this many seqs for their partner, then are dropped
  int camera_queue = 4;             //!< CAMERA frames LCM holds while the stage observes one (the newest pair
                                    //!< is observed next, the others skipped; LCM drops arrivals beyond this,
                                    //!< the newest: 4 frames cover a 130 ms observation at 30 fps; LCM's own is 30)
  // Hands that are hand-shaped and within reach (ours, not the paper's: colour alone finds walls, wood and bare
  // forearms on real photos; hands README, ablation table). 0 turns each off.
  double max_blob_hand_areas = 4.0;  //!< a skin component with more than this many hand squares outside the user
                                     //!< box is no hand (a wall, wood; a bare forearm and hand reaching out is ~2)
  double shoulder_half_ratio = 0.35; //!< the shoulders sit this many box widths either side of p_uc
  double reach_ratio = 1.6;          //!< Alg. 1: a hand lies within this many box widths of its shoulder
  double out_min_angle_deg = 25.0;   //!< Alg. 1: below the shoulder line, a hand this far from straight down (seen
                                     //!< from its shoulder) or more: a hanging forearm beside the body is not OUT
                                     //!< (the paper's DOWN arm points 30 deg from down)
  bool out_not_beside_hanging_forearm = true;  //!< Alg. 1: no hand on a side where a forearm hangs at rest inside the
                                              //!< box (a skin component front_max_upright times taller than wide in
                                              //!< the outer half of the box, below the body centre): that arm is down
  bool arm_connected = true;         //!< Alg. 1: the hand must be joined to the torso by skin or the torso's
                                     //!< clothing colours (an arm, bent or straight, bare or in sleeves)
  double arm_radius_ratio = 0.03;    //!< gaps up to twice this many box widths along the arm are closed
  double torso_inset_ratio = 0.2;    //!< the torso is the box less this many box widths each side: its colours
                                     //!< are the clothing's, and an arm must reach it (the box's margins are scenery)
  double front_max_upright = 2.5;    //!< Alg. 2: a skin component this many times taller than wide that reaches
                                     //!< below the body centre is a hanging forearm, not a hand in front (0 = off)
  double front_max_hand_areas = 4.0; //!< Alg. 2: a skin component larger than this many hand squares is the torso
                                     //!< (an orange shirt, a bare chest), not a hand in front of it (0 = off)
  bool needs_body_centre = true;  //!< while p_bc (and the hand square around it) is out of the image (the drone high
                                  //!< and close, the hips below the frame): Alg. 2 judges no hand in front (a resting
                                  //!< hand at the bottom edge is "higher"), and Alg. 1 no hand below the shoulders
                                  //!< whose square the image border cuts (a resting hand, or scenery, at the cut edge)

  template <class V>
  void visit(V& v) {
    v("method", method, "hands method: skin (the paper's Alg. 1/2 on a skin table) or pose (body landmarks)");
    v.group("pose", pose);
    v.group("pose_gesture", pose_gesture);
    v.group("skin", skin);
    v("roi_extend_side", roi_extend_side, 0.0, 10.0, "search rectangle: added each side, user box widths");
    v("roi_extend_top", roi_extend_top, 0.0, 5.0, "search rectangle: added above, user box heights");
    v("roi_extend_bottom", roi_extend_bottom, 0.0, 5.0, "search rectangle: added below, user box heights");
    v("face_remove_ratio", face_remove_ratio, 0.0, 1.0, "top fraction of the user box removed (face, neck)");
    v("legs_remove_ratio", legs_remove_ratio, 0.0, 1.0, "bottom fraction of the user box removed (legs, feet)");
    v("neck_in_faces", neck_in_faces, 0.0, 5.0, "face heights below a known face removed as neck (0 = the box ratio alone; ours)");
    v("shoulder_centre_ratio", shoulder_centre_ratio, 0.0, 1.0, "p_uc: fraction of box height below the top");
    v("body_centre_ratio", body_centre_ratio, 0.0, 1.0, "p_bc: fraction of box height below the top (paper: centre)");
    v("hand_square_ratio", hand_square_ratio, 0.01, 1.0, "hand square side / box width (paper 1/4)");
    v("out_min_skin", out_min_skin, 0, 1000000, "Alg. 1: skin pixels outside the box needed, more than (paper 30)");
    v("lambda1", lambda1, 0.0, 100.0, "Alg. 1 weight of F_skin (paper 0.5)");
    v("lambda2", lambda2, -100.0, 100.0, "Alg. 1 weight of height above p_uc (paper 0.2)");
    v("lambda3", lambda3, 0.0, 100.0, "Alg. 2 weight of F_skin (paper 0.013)");
    v("front_gate_ratio", front_gate_ratio, 0.0, 1.0, "Alg. 2: |p_bc.x - p.x| below ratio x box width (paper 1/5)");
    v("front_min_skin", front_min_skin, 0, 1000000, "Alg. 2: F_skin needed, more than (paper 30)");
    v("min_skin_square_share", min_skin_square_share, 0.0, 1.0, "Alg. 1 and 2 need at most this share of the hand square's area in skin (small far users; 0 = off; ours)");
    v("down_min_skin_square_share", down_min_skin_square_share, 0.0, 1.0, "Alg. 1, hand below the shoulder line: at most this share of the hand square in skin outside (0 = min_skin_square_share; ours)");
    v("match_window", match_window, 1, 1000, "CAMERA/USER_TRACK pairing: seqs an unmatched one waits before it is dropped");
    v("camera_queue", camera_queue, 1, 1000, "CAMERA frames held while one is observed (the newest pair is observed next; skipped frames are counted in HEALTH.dropped)");
    v("max_blob_hand_areas", max_blob_hand_areas, 0.0, 1000.0, "skin component with more hand squares outside the box is no hand (0 = off; ours)");
    v("shoulder_half_ratio", shoulder_half_ratio, 0.0, 2.0, "shoulders this many box widths either side of p_uc");
    v("reach_ratio", reach_ratio, 0.0, 10.0, "Alg. 1: hand within this many box widths of its shoulder (0 = off; ours)");
    v("out_min_angle_deg", out_min_angle_deg, 0.0, 90.0, "Alg. 1: hand below the shoulders this far from straight down at least (0 = off; ours)");
    v("out_not_beside_hanging_forearm", out_not_beside_hanging_forearm, "Alg. 1: no hand on a side whose forearm hangs at rest in the box (ours)");
    v("arm_connected", arm_connected, "Alg. 1: the hand must be joined to the torso by skin or clothing colours (ours)");
    v("arm_radius_ratio", arm_radius_ratio, 0.005, 0.5, "arm_connected closes gaps up to twice this, box widths");
    v("torso_inset_ratio", torso_inset_ratio, 0.0, 0.45, "torso = box less this many box widths each side (arm_connected; ours)");
    v("front_max_upright", front_max_upright, 0.0, 100.0, "Alg. 2: taller/wide ratio of a hanging forearm's skin, dropped (0 = off; ours)");
    v("front_max_hand_areas", front_max_hand_areas, 0.0, 1000.0, "Alg. 2: skin component of more hand squares is the torso, dropped (0 = off; ours)");
    v("needs_body_centre", needs_body_centre, "body centre out of the image: no FRONT hand, no OUT hand below the shoulders cut by the border (ours)");
  }
  void check(const ParamCheck& c) const {
    c.choice("method", method, {"pose", "skin"});
    // The face/neck band and the legs band are cut from the same box: together they must leave some of it.
    c.require(face_remove_ratio + legs_remove_ratio < 1.0, "legs_remove_ratio",
              "face_remove_ratio + legs_remove_ratio = " +
                  ParamWriter::format_number(face_remove_ratio + legs_remove_ratio, false) +
                  " removes the whole user box (must be below 1)");
  }
};

// Hands' section of the config file (services/system assembles the whole file from every stage's).
inline void add_hands_sections(ConfigSchema& schema) { schema.section<HandsParams>("hands"); }

}  // namespace gpilot
