// The paper's hand detection for one frame and one user box (w = box width):
//   skin mask (one table lookup a pixel) inside the search rectangle extended from the user box, opened
//   (erode + dilate, ours) against background specks, with the face/neck and legs/feet rows of the box removed; F_skin(p) = skin pixels in the w/4 square centred at p,
//   from an integral image (O(1) a pixel);
//   Alg. 1: more than out_min_skin skin pixels outside the box -> argmax over them of
//           |p_uc.x - p.x| + λ2 (p_uc.y - p.y) + λ1 F_skin(p), result p - p_uc (KIND OUT);
//   Alg. 2 (only if Alg. 1 found nothing): argmax over skin pixels inside the box of
//           -|p_bc.x - p.x| + λ3 F_skin(p), accepted if |p_bc.x - p.x| < w/5 and F_skin > 30, result p - p_bc.
// Ours, on top (each a config value, 0 = off): skin components with more than a few hand squares outside the
// user box are dropped (walls, wood); Alg. 1 counts only skin within reach of a shoulder and, below the shoulder line, far enough
// from straight down that a hanging forearm is not a stretched-out arm; and an OUT hand must hang on an arm:
// arm-coloured pixels (skin, the user's clothing) join it to the torso (not a sign, a dome, someone's face);
// and while the body centre is out of the image, Alg. 2 judges no hand (higher/lower than a centre out of view
// is unknown: a resting hand at the frame's bottom edge is above a centre below the frame) and Alg. 1 no hand
// below the shoulders that the image border cuts.
// Pure: no LCM, no clock. Image axes: x right, y down, pixels.
#pragma once

#include <vector>

#include <array>
#include <optional>

#include <opencv2/core.hpp>

#include "hands/clothing_colours.hpp"
#include "hands/hands_params.hpp"
#include "hands/skin_model.hpp"

namespace gpilot {

enum class HandKind { None = 0, Out = 1, Front = 2 };  // same values as hand_obs_t::KIND_*

const char* hand_kind_name(HandKind k);

// Where the paper's reference points and rectangles are for one user box.
struct HandGeometry {
  cv::Rect box;                 //!< user box, whole pixels, clipped to the image
  cv::Rect roi;                 //!< search rectangle (box extended), clipped to the image
  cv::Point2f shoulder_centre;  //!< p_uc
  cv::Point2f body_centre;      //!< p_bc
  float width = 0;              //!< w: the user box width as given (the clipped box may be narrower)
  int hand_side = 0;            //!< hand square side, pixels (w/4)
  int open_radius = 0;          //!< skin mask opening radius, pixels (0 = none)
  int face_rows_end = 0;        //!< box rows y < this are removed (face, neck)
  int legs_rows_begin = 0;      //!< box rows y >= this are removed (legs, feet)
  cv::Size image;               //!< the frame's size
  bool body_centre_in_view = false;  //!< p_bc and the hand square around it lie inside the image
  bool valid = false;           //!< false for a box too small or off the image
};

// user_box: x, y (top-left), width, height in pixels. image: the frame's size.
// face: the user's face in this frame when known (hands.neck_in_faces: the rows below it down to the neck's
// end are removed too, whatever the box's own ratio says).
HandGeometry hand_geometry(const HandsParams& params, const cv::Rect2f& user_box, cv::Size image,
                           const std::optional<cv::Rect2f>& face = std::nullopt);
// The torso (its clothing): between the face rows and the body centre, the box's width less torso_inset_ratio
// each side; empty when the box leaves none in the image.
cv::Rect torso_rect(const HandsParams& params, const HandGeometry& geometry);

struct HandResult {
  HandKind kind = HandKind::None;
  HandGeometry geometry;
  cv::Point hand{0, 0};      //!< chosen pixel (OUT/FRONT)
  cv::Point2f vector{0, 0};  //!< hand - p_uc (OUT) or hand - p_bc (FRONT); zero for NONE
  cv::Rect hand_box;         //!< the hand square at the chosen pixel (empty for NONE)
  int hand_skin = 0;         //!< F_skin at the chosen pixel
  int skin_outside = 0;      //!< skin pixels outside the box, inside the search rectangle
  int skin_inside = 0;       //!< skin pixels inside the box after the removals
  int front_candidate_skin = 0;  //!< F_skin of Alg. 2's argmax even when its gates refused it
  int blobs_dropped = 0;         //!< skin components too large for a hand
  int armless_dropped = 0;       //!< Alg. 1 candidates dropped: no arm from the shoulder to them
  int upright_dropped = 0;       //!< Alg. 2 candidates dropped: a forearm hanging at the torso's edge
  bool front_out_of_view = false;  //!< Alg. 2 found a hand but the body centre is out of the image: not judged
  bool colourless = false;         //!< the frame has no colour (SkinHandMethod, colour_check.hpp): nothing learnt or looked for
};

class HandDetector {
 public:
  // Throws SkinModelError if the classifier is empty.
  HandDetector(const HandsParams& params, SkinClassifier skin);

  // Whole stage for one frame (CV_8UC3 BGR), with the detector's own classifier or `skin` (e.g. an adapted one).
  // clothing: the user's clothing colours learnt from this frame's torso (torso_rect of this box and face), which
  // the arm test reads; none: the detector learns them from this frame itself.
  HandResult detect(const cv::Mat& bgr, const cv::Rect2f& user_box, const SkinClassifier* skin = nullptr,
                    const std::optional<cv::Rect2f>& face = std::nullopt, const ClothingColours* clothing = nullptr);

  // Alg. 1 then Alg. 2 on a ready skin mask (CV_8UC1, nonzero = skin) whose top-left pixel is image pixel
  // origin. Removals are NOT applied here: the mask is used as given (detect() applies them first).
  HandResult detect_on_mask(const cv::Mat& mask, cv::Point origin, const HandGeometry& geometry);

  // The skin mask of the last detect() over its search rectangle (0/1, removals applied), and where it is.
  const cv::Mat& last_mask() const { return mask_; }
  cv::Rect last_roi() const { return last_roi_; }
  const HandsParams& params() const { return params_; }
  // The trained table's classifier (the one detect() uses when given none).
  const SkinClassifier& classifier() const { return skin_; }

 private:
  HandResult run(const cv::Mat& mask01, cv::Point origin, const HandGeometry& geometry);
  // detect()'s steps. The skin of the search rectangle into mask_ (opened, face and legs rows cleared); returns
  // the skin the arm test reads: unopened_ (the same rows cleared) when the arm rule and the opening are on,
  // else mask_ itself.
  const cv::Mat& make_skin_mask(const cv::Mat& bgr, const SkinClassifier& skin, const HandGeometry& geometry);
  // Alg. 1's result kept only for a hand joined to the torso by an arm (arm_connected): each armless candidate
  // is erased and Alg. 1 runs again, after kMaxDroppedCandidates the skin outside the box goes. Returns how
  // many were dropped. clothing: as detect()'s.
  int out_on_an_arm(const cv::Mat& bgr, const cv::Mat& arm_skin, const HandGeometry& geometry,
                    const ClothingColours* clothing, HandResult& res);
  // Alg. 2's result dropped while it is a hanging forearm or torso-sized, and Alg. 2 run again; after
  // kMaxDroppedCandidates no hand (res.upright_dropped counts them either way).
  void front_not_a_forearm(const HandGeometry& geometry, HandResult& res);
  // Clears skin components too large to be a hand from mask01 (labelled in labels_: n labels, 0 background),
  // and the same pixels from `also` if given; marks them in blob_dropped_.
  int drop_large_blobs(cv::Mat& mask01, const HandGeometry& geometry, int n, cv::Mat* also = nullptr);
  // Sets hanging_ from the n components of stats_ not dropped: the sides (image left, right) where a forearm
  // hangs at rest beside the body (n 0: none looked for).
  void find_hanging_forearms(const HandGeometry& geometry, int n);
  // Clears the skin component of mask_ holding an image pixel (a candidate this frame will not take).
  void erase_component(const HandGeometry& geometry, cv::Point pixel);
  // Whether arm-coloured pixels (`skin` over the search rectangle, the colours `clothing` says are worn) join
  // the hand to the torso.
  bool on_an_arm(const cv::Mat& bgr, const cv::Mat& skin, const HandGeometry& geometry,
                 const ClothingColours& clothing, cv::Point hand);

  static constexpr int kMaxDroppedCandidates = 3;   // then the algorithm gives up on this frame

  HandsParams params_;
  SkinClassifier skin_;
  cv::Mat mask_, unopened_, integral_, labels_, arm_, stats_, centroids_;
  std::vector<uint8_t> blob_dropped_;  //!< per label of labels_: cleared by drop_large_blobs
  std::array<bool, 2> hanging_{};  //!< a forearm hangs at rest on the image's left / right side of p_uc
  ClothingColours own_clothing_;  //!< learnt here when detect() is given no clothing colours
  cv::Rect last_roi_;
};

}  // namespace gpilot
