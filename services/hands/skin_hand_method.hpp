// The skin method (hands.method skin, the paper's): learns the user's skin (from the face the tracker found),
// the scene's colours (around the user) and the user's clothing colours (the torso, ClothingColours: once a
// frame, for both the skin model and the arm test) on top of the trained skin table, then runs the paper's
// Alg. 1/2 (HandDetector) with the adapted classifier on the tracker's box. The state depends only on the
// frames and user views seen; a new track_id starts over. Pure: no LCM, no clock. Built by make_hand_method
// (hands_core_factory.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "hands/clothing_colours.hpp"
#include "hands/hand_detector.hpp"
#include "hands/hand_method.hpp"
#include "hands/hands_params.hpp"
#include "hands/skin_adapter.hpp"
#include "hands/skin_model.hpp"

namespace gpilot {

class SkinHandMethod : public HandMethod {
 public:
  // Throws SkinModelError for an empty model (or one without likelihoods while hands.skin.adapt is on).
  // model_path: where the model came from (HEALTH's description).
  SkinHandMethod(const HandsParams& params, const SkinModel& prior, std::string model_path = "");

  // The shared observation, with the skin part (SkinDiagnostics). A frame without colour is refused (nothing
  // learnt); a view that is not tracking gives NONE on its box. utime: unused (the skin method keeps no time).
  HandsOutput observe(const cv::Mat& bgr, const UserView& user, int64_t utime) override;
  void reset() override;
  std::string description() const override { return "skin model " + model_path_; }

  // Alg. 1/2's own result for a tracked user: learns from this frame (user skin from the face, the scene outside
  // the search rectangle, the clothing from the torso), then detects on the user box as given (the tracker's).
  // bgr: CV_8UC3. A frame without colour (hands.skin.min_colour_fraction) gives NONE with `colourless` set, and
  // nothing is learnt from it.
  HandResult detect(const cv::Mat& bgr, const UserView& user);

  SkinAdaptation adaptation() const {
    return {adapter_.user_samples(), adapter_.scene_samples(), adapter_.changed_fraction()};
  }
  const cv::Mat& last_mask() const { return detector_.last_mask(); }
  cv::Rect last_roi() const { return detector_.last_roi(); }
  const HandsParams& params() const { return detector_.params(); }

 private:
  HandDetector detector_;
  SkinAdapter adapter_;
  ClothingColours clothing_;  //!< learnt from each frame's torso; read by adapter_ (C) and detector_ (the arm test)
  std::string model_path_;
  int32_t track_id_ = -1;
  const SkinClassifier* judged_with_ = nullptr;  //!< the classifier the last detect() used (none: the table's)
  //! The last face given for this track and the box it came with: carried along with the box (carried_with_box)
  //! on frames without one.
  struct FaceWithBox {
    cv::Rect2d face, box;
  };
  std::optional<FaceWithBox> last_face_;
};

}  // namespace gpilot
