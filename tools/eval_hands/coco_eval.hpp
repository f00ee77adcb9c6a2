// gpilot-eval-hands --coco: the hands stage (make_hand_method, a fresh start per person) on every annotated person
// of a COCO person-keypoints file, scored against the keypoint truth (keypoint_truth.hpp, hands_score.hpp).
// Writes the per-person CSV and annotated PNGs on request; progress on stderr.
#pragma once

#include <string>

#include "hands/hands_params.hpp"
#include "hands_score.hpp"
#include "tracker/tracker_params.hpp"
#include "user_view_choice.hpp"

namespace gpilot {

struct CocoEvalOptions {
  std::string annotations;  //!< COCO person-keypoints JSON
  std::string images_dir;   //!< folder of the images (images[].file_name inside it)
  BoxMode box = BoxMode::Annotation;
  std::string csv_path;     //!< "" = none
  std::string png_dir;      //!< "" = none
  bool progress = true;     //!< a line on stderr per image
};

// Throws CocoError for a bad annotation file, std::runtime_error for an unwritable CSV or a missing cascade.
// An image that does not load is counted (image_unreadable) and its people skipped.
HandsScoreboard run_coco_eval(const CocoEvalOptions& options, const HandsParams& hands, const TrackerParams& tracker);

}  // namespace gpilot
