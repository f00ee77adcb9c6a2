// The skin model that learns this user and this scene (the paper's future work), on top of the trained table:
//   P(c|skin) ~ P_table(c|skin) + a U(c)            U: this user's skin, from the face the tracker found
//                                                   (the cheek band of the face box, pixels the table already
//                                                   calls likely skin), a = adapt.user_weight: it only adds,
//                                                   so a wrong face cannot make the user's hands non-skin
//   P(c|other) = (1 - b - k) P_table(c|not)          S: the scene, pixels outside the hands' search rectangle,
//                + b S(c) + k C(c)                  with decay, b <= adapt.scene_weight; C: the user's clothing,
//                                                   the torso of the box (ClothingColours), k <= adapt.clothing_weight
//   skin iff P(c|skin) P(skin) / (P(c|skin) P(skin) + P(c|other) P(not)) > skin.threshold  (Bayes, as Jones & Rehg)
// so a wall colour that is everywhere around the user stops being skin, an orange shirt is the shirt, and the
// user's own tone stays skin.
// The table is the floor: the user's histogram only adds skin colours, and the scene's share is bounded by b,
// so one bad face or one odd frame cannot take the model over.
// State depends only on the frames, boxes and faces given; no clock.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "hands/clothing_colours.hpp"
#include "hands/hands_params.hpp"
#include "hands/skin_model.hpp"

namespace gpilot {

class SkinAdapter {
 public:
  // Throws SkinModelError when adaptation is on and the model has no likelihood tables (retrain it).
  SkinAdapter(const SkinParams& params, const SkinModel& prior);

  // Learns the user's skin from the face box (pixels, clipped to the image). bgr: CV_8UC3.
  void learn_user(const cv::Mat& bgr, const cv::Rect2f& face);
  // Learns the scene from every adapt.scene_stride-th pixel of bgr outside `exclude` (the search rectangle).
  void learn_scene(const cv::Mat& bgr, const cv::Rect& exclude);
  // Forgets both (the trained table alone).
  void reset();

  // The classifier a frame is judged with: counts the frame, and rebuilds the classifier from the state learnt
  // so far, `clothing`'s C(c) included, when that changed (a track's first state at once, later ones every
  // adapt.rebuild_frames frames: the smoothing is the cost). Once a frame.
  const SkinClassifier& classifier_for_frame(const ClothingColours* clothing = nullptr);
  // The classifier as last built; reading it counts no frame and rebuilds nothing.
  const SkinClassifier& classifier() const { return adapted_; }

  int64_t user_samples() const { return user_samples_; }
  int64_t scene_samples() const { return scene_samples_; }
  //! Per skin-table bin: one of the user's skin colours, which are never clothing (ClothingColours::learn); empty
  //! until a face was learnt, and with adapt.clothing_weight 0.
  const std::vector<uint8_t>& user_skin_colours() const { return user_colour_; }
  //! Fraction of colour bins whose decision differs from the trained table's (after the last rebuild).
  double changed_fraction() const { return changed_fraction_; }

 private:
  void rebuild(const ClothingColours* clothing);

  SkinParams p_;
  SkinModel prior_;
  SkinClassifier prior_classifier_, adapted_;
  // Every adapt.scene_stride-th pixel of bgr outside `exclude` into sample_; their number.
  double sample_outside(const cv::Mat& bgr, const cv::Rect& exclude);

  std::vector<double> user_, scene_, sample_;
  std::vector<double> user_smooth_;   // user_ smoothed (smoothing_sigma), as rebuild() uses it
  std::vector<uint8_t> user_colour_;  // per bin: one of the user's skin colours (kept out of the clothing)
  int64_t user_samples_ = 0, scene_samples_ = 0;
  int64_t clothing_samples_seen_ = 0;  // the clothing's samples() at the last frame: another count is a change
  int frames_since_rebuild_ = 0;
  bool dirty_ = false, built_ = false;
  double changed_fraction_ = 0;
};

}  // namespace gpilot
