// The body box of a face, checked against the image before a track starts on it (issue 13: on held-out videos
// a dancing person's face-derived box was much larger than the person and ran off the bottom of the frame).
// The head-body ratios give the preset box; then
//  - a face whose preset box lies mostly outside the frame (the body below the bottom edge) is refused;
//  - a face with no torso in view under it, or whose torso colours are those of the background beside the box
//    (a face on a poster or a T-shirt: the same poster or shirt below as beside), is refused;
//  - else the box's width, bottom and horizontal centre are fitted to the person's colour silhouette
//    (P(person | colour) from the band under the face against the strips beside the box), within bounds.
// Plain function, no state: the same frame and face give the same answer.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "body_proportions.hpp"
#include "tracker_params.hpp"

namespace gpilot {

enum class FaceRefusal {
  kNone = 0,
  kOffFrame,      //!< the preset body box is mostly outside the frame (body_fit.min_in_frame)
  kNoTorso,       //!< the torso sample under the face is mostly outside the frame (body_fit.min_torso_in_frame)
  kNoBodyColour,  //!< the torso's colours are the background's beside the box (body_fit.min_separation)
};
constexpr int kFaceRefusals = 4;
//! Why a face was refused, for HEALTH ("" for kNone).
const char* refusal_text(FaceRefusal r);

struct BodyFit {
  FaceRefusal refused = FaceRefusal::kNone;
  BodyProportions body;      //!< the ratios of the box below (the preset's, or fitted)
  cv::Rect2d box;            //!< body_from_face(face, body): the box a track starts on (not clipped)
  // What was measured (diagnostics and tests):
  double in_frame = 0.0;     //!< fraction of the preset box's area inside the frame
  double separation = -1.0;  //!< 1 - Bhattacharyya(torso, beside) colours; -1: not measured
  double width_ratio = 1.0;  //!< silhouette width / preset width (1 when not seen)
  double height_ratio = 1.0; //!< silhouette bottom - box top / preset height (1 when not seen)
  double shift = 0.0;        //!< silhouette centre - face centre, face widths (0 when not seen)
  bool width_seen = false;   //!< at least one side of the silhouette seen inside the frame
  bool height_seen = false;  //!< the silhouette's bottom seen inside the frame
};

// frame: CV_8UC3 (BGR) or CV_8UC1; face: the cascade's face box in frame pixels (positive size). preset: the
// head-body ratios (TrackerParams::body()).
BodyFit fit_body(const cv::Mat& frame, const cv::Rect2d& face, const BodyProportions& preset, const BodyFitParams& p);

// The colours of the torso under a face (fit_body's torso sample: torso_*_in_faces of p), as a histogram of
// chromaticity (r / (b + g + r), g / (b + g + r), bins x bins; a gain on the light leaves it unchanged) over
// the pixels whose mean level is at least dark_level (a dark pixel's chromaticity is noise), read on a grid
// where the face is at most p.fit_face_px wide; normalised to sum 1. Empty for a grey frame, or when no pixel
// of the sample is in view and bright enough. What tells the user from a look-alike beside them (issue 13:
// a bystander with the same face passing in front): their clothes.
std::vector<float> torso_colours(const cv::Mat& frame, const cv::Rect2d& face, const BodyFitParams& p, int bins,
                                 double dark_level);
// Bhattacharyya coefficient of two normalised histograms (1: the same colours, 0: none shared); -1 when either is
// empty or they differ in size (nothing to compare).
double colour_match(const std::vector<float>& a, const std::vector<float>& b);

}  // namespace gpilot
