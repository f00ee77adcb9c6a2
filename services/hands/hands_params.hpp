// Parameters of gpilot-hands (section `hands`): skin model, search rectangle, and the paper's Alg. 1 and 2.
#pragma once

#include <string>

namespace gpilot {

struct SkinParams {
  std::string model = "data/skin/skin_model.yaml";  //!< trained histogram model (gpilot-skin-train), relative to the project root
  // 0.75, not 0.5: background photographs have many colours the smoothed table puts at P 0.5..0.75 (building.jpg:
  // 8.4 % of its pixels at 0.5, 4.1 % at 0.75) while held-out skin F1 only drops from 0.900 to 0.876 (data/skin/README.md).
  double threshold = 0.75;          //!< P(skin | rgb) above this is skin
  // Not in the paper: a morphological opening (erode then dilate, square of side 2r+1) of the skin mask removes
  // the thin edges and specks a textured background leaves, which Alg. 1 would otherwise count outside the box.
  // r = round(open_radius_ratio x user box width): 2 px for an 85 px box, so a hand (w/4 wide) survives it.
  double open_radius_ratio = 0.025;  //!< opening radius / box width (0 = off)

  template <class V>
  void visit(V& v) {
    v("model", model, "skin model file from gpilot-skin-train (relative paths: from the project root)");
    v("threshold", threshold, 0.0, 1.0, "P(skin|colour) above this is skin");
    v("open_radius_ratio", open_radius_ratio, 0.0, 0.25, "skin mask opening radius / box width (0 = off; ours, not the paper's)");
  }
};

struct HandsParams {
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
  double shoulder_centre_ratio = 0.2;  //!< p_uc sits this fraction of the box height below its top, centred
  double body_centre_ratio = 0.5;   //!< p_bc: the box centre (the paper)
  double hand_square_ratio = 0.25;  //!< hand square side = ratio × box width (paper w/4)
  int out_min_skin = 30;            //!< Alg. 1 runs only with more than this many skin pixels outside the box (paper 30)
  double lambda1 = 0.5;             //!< Alg. 1 weight of F_skin (paper λ1)
  double lambda2 = 0.2;             //!< Alg. 1 weight of the height above p_uc (paper λ2)
  double lambda3 = 0.013;           //!< Alg. 2 weight of F_skin (paper λ3)
  double front_gate_ratio = 0.2;    //!< Alg. 2 accepts |p_bc.x - p.x| < ratio × w (paper w/5)
  int front_min_skin = 30;          //!< Alg. 2 accepts F_skin above this (paper 30)
  int match_window = 15;            //!< frames/tracks wait this many seqs for their partner, then are dropped

  template <class V>
  void visit(V& v) {
    v.group("skin", skin);
    v("roi_extend_side", roi_extend_side, 0.0, 10.0, "search rectangle: added each side, user box widths");
    v("roi_extend_top", roi_extend_top, 0.0, 5.0, "search rectangle: added above, user box heights");
    v("roi_extend_bottom", roi_extend_bottom, 0.0, 5.0, "search rectangle: added below, user box heights");
    v("face_remove_ratio", face_remove_ratio, 0.0, 1.0, "top fraction of the user box removed (face, neck)");
    v("legs_remove_ratio", legs_remove_ratio, 0.0, 1.0, "bottom fraction of the user box removed (legs, feet)");
    v("shoulder_centre_ratio", shoulder_centre_ratio, 0.0, 1.0, "p_uc: fraction of box height below the top");
    v("body_centre_ratio", body_centre_ratio, 0.0, 1.0, "p_bc: fraction of box height below the top (paper: centre)");
    v("hand_square_ratio", hand_square_ratio, 0.01, 1.0, "hand square side / box width (paper 1/4)");
    v("out_min_skin", out_min_skin, 0, 1000000, "Alg. 1: skin pixels outside the box needed, more than (paper 30)");
    v("lambda1", lambda1, 0.0, 100.0, "Alg. 1 weight of F_skin (paper 0.5)");
    v("lambda2", lambda2, -100.0, 100.0, "Alg. 1 weight of height above p_uc (paper 0.2)");
    v("lambda3", lambda3, 0.0, 100.0, "Alg. 2 weight of F_skin (paper 0.013)");
    v("front_gate_ratio", front_gate_ratio, 0.0, 1.0, "Alg. 2: |p_bc.x - p.x| below ratio x box width (paper 1/5)");
    v("front_min_skin", front_min_skin, 0, 1000000, "Alg. 2: F_skin needed, more than (paper 30)");
    v("match_window", match_window, 1, 1000, "CAMERA/USER_TRACK pairing: seqs an unmatched one waits before it is dropped");
  }
};

}  // namespace gpilot
