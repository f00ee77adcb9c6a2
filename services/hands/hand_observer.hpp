// The hands stage's core for one user: learns the user's skin (from the face the tracker found) and the
// scene's colours (around the user) on top of the trained skin table, then runs the hand detector with the
// adapted classifier. The state depends only on the frames and user views seen; a new track_id starts over.
// Pure: no LCM, no clock. Used by gpilot-hands, gpilot-replay, gpilot-eval-hands and the tests.
#pragma once

#include <cstdint>
#include <optional>

#include <opencv2/core.hpp>

#include "body_proportions.hpp"
#include "hands/hand_detector.hpp"
#include "hands/hands_params.hpp"
#include "hands/skin_adapter.hpp"
#include "hands/skin_model.hpp"

namespace gpilot {

// What the hands stage knows of the user in one frame (from USER_TRACK).
struct UserView {
  cv::Rect2f box;                   //!< body box, pixels (x, y top-left, width, height)
  std::optional<cv::Rect2f> face;   //!< the user's face box in this frame, pixels, when the tracker has one
  int32_t track_id = 0;             //!< a new id forgets what was learnt
};

// How far the skin model has moved from the trained table.
struct SkinAdaptation {
  int64_t user_samples = 0;     //!< face pixels learnt as this user's skin (after decay)
  int64_t scene_samples = 0;    //!< background pixels learnt (after decay)
  double changed_fraction = 0;  //!< fraction of colour bins whose skin/not-skin decision differs from the prior's
};

class HandObserver {
 public:
  // Throws SkinModelError for an empty model (or one without likelihoods while hands.skin.adapt is on).
  HandObserver(const HandsParams& params, const SkinModel& prior);

  // Learns from this frame (user skin from the face, the scene outside the search rectangle), then detects on
  // the user box as given (the tracker's: the one body box from the tracker to decide). bgr: CV_8UC3. A frame without colour
  // (hands.skin.min_colour_fraction) gives NONE with `colourless` set, and nothing is learnt from it.
  HandResult observe(const cv::Mat& bgr, const UserView& user);
  // Forgets the user and the scene (the trained table alone again).
  void reset();

  SkinAdaptation adaptation() const {
    return {adapter_.user_samples(), adapter_.scene_samples(), adapter_.changed_fraction()};
  }
  // The skin classifier as learnt so far (the one the last observe() used).
  const SkinClassifier& skin_classifier() { return adapter_.classifier(); }
  const cv::Mat& last_mask() const { return detector_.last_mask(); }
  cv::Rect last_roi() const { return detector_.last_roi(); }
  const HandsParams& params() const { return detector_.params(); }

 private:
  HandDetector detector_;
  SkinAdapter adapter_;
  int32_t track_id_ = -1;
  //! The last face given for this track and the box it came with: carried along with the box (carried_with_box)
  //! on frames without one.
  struct FaceWithBox {
    cv::Rect2d face, box;
  };
  std::optional<FaceWithBox> last_face_;
};

}  // namespace gpilot
