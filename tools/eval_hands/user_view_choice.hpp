// Which user box and face the hands stage is given for one annotated person of a photo:
//   annotation: the largest Haar face in the top part of the annotation's bbox, searched in the window the
//               tracker's face re-check uses for a box (face_recheck_window), and the body box the tracker makes
//               from it (body_from_face, tracker params); no face there: the annotation's bbox, no face.
//   face:       the body box the tracker would make from this person's face: the largest Haar face in the
//               head region spanned by the nose/eyes/ears keypoints (their face box grown 2x), accepted if
//               its centre lies in that face box grown 1.5x; body box = body_from_face(face, tracker params)
//               (unclipped, as the tracker starts a track). No face: no view ("no face").
//   keypoints:  as face, with the face box the nose/eyes/ears keypoints span (keypoint_face_box) in place of
//               the cascade's: the hands stage apart from face finding, as if the tracker never missed a face.
#pragma once

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "hands/hand_method.hpp"
#include "keypoint_truth.hpp"
#include "tracker/face_detector.hpp"
#include "tracker/tracker_params.hpp"

namespace gpilot {

enum class BoxMode { Annotation, Face, Keypoints };
const char* box_mode_name(BoxMode m);  // "annotation", "face", "keypoints"

struct ChosenView {
  std::optional<UserView> view;    //!< none: no face in face mode (the person is not run)
  std::optional<cv::Rect2f> face;  //!< the Haar face used (both modes), if any
  cv::Rect search_window;          //!< where the face was looked for (image pixels, clipped)
  std::string note;                //!< why there is no view / no face
};

class UserViewChooser {
 public:
  // Throws std::runtime_error when the cascade does not load.
  UserViewChooser(const TrackerParams& tracker, BoxMode mode);

  ChosenView choose(const cv::Mat& bgr, const cv::Rect2f& annotation_box, const PersonKeypointTruth& truth,
                    int32_t track_id);

  BoxMode mode() const { return mode_; }

 private:
  TrackerParams tracker_;
  BoxMode mode_;
  FaceDetector faces_;
};

}  // namespace gpilot
