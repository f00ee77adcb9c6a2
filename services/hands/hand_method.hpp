// A hands method: what finds the paper's observation (OUT: a stretched-out hand, vector from the shoulder
// centre p_uc; FRONT: a hand in front of the body, vector from the body centre p_bc; NONE) for the tracked user
// in one frame. hands.method picks one (hands_core_factory.hpp). Every method measures on the box the tracker
// gives (UserView::box, the one body box from the tracker to decide); what only one method knows travels in its
// own part of the result. Pure: no LCM, no clock (a frame's time comes in).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "hands/hand_detector.hpp"
#include "pose/pose_landmarks.hpp"

namespace gpilot {

// What the hands stage knows of the user in one frame (from USER_TRACK).
struct UserView {
  cv::Rect2f box;                   //!< the user's body box, pixels (x, y top-left, width, height): the tracker's
  std::optional<cv::Rect2f> face;   //!< the user's face box in this frame, pixels, when the tracker has one
  int32_t track_id = 0;             //!< a new id forgets what was learnt
  bool tracking = true;             //!< false: the track is LOST or SEARCHING; NONE on the box, nothing learnt
};

// How far the skin model has moved from the trained table.
struct SkinAdaptation {
  int64_t user_samples = 0;     //!< face pixels learnt as this user's skin (after decay)
  int64_t scene_samples = 0;    //!< background pixels learnt (after decay)
  double changed_fraction = 0;  //!< fraction of colour bins whose skin/not-skin decision differs from the prior's
};

// The skin method's evidence for one frame (hands.method skin). mask and classifier are the method's own
// buffers: valid until its next observe().
struct SkinDiagnostics {
  HandResult detection;                       //!< Alg. 1/2's result: its geometry (search rectangle, bands), counts
  SkinAdaptation adaptation;                  //!< the skin model learnt for this track so far
  cv::Mat mask;                               //!< skin mask (0/1, removals applied) over roi; empty when not run
  cv::Rect roi;                               //!< where mask lies, image pixels
  const SkinClassifier* classifier = nullptr; //!< the (adapted) classifier this frame was judged with
};

// The pose method's evidence for one frame (hands.method pose; filled by its method).
struct PoseDiagnostics {
  PoseLandmarks landmarks{};  //!< BlazePose's 33 landmarks, image pixels
  double score = 0;           //!< the landmark model's pose flag, 0..1
  std::string reading;        //!< how the arms were read: "<rule>; left <ARM>, right <ARM>" ("" without a pose)
};

// One frame's observation, whatever the method: every position is on user_box (the tracker's box as given).
struct HandsOutput {
  HandKind kind = HandKind::None;
  cv::Point2f vector{0, 0};           //!< hand - p_uc (OUT) or hand - p_bc (FRONT), pixels, image axes; 0 for NONE
  cv::Point2f hand{0, 0};             //!< the hand's position (OUT, FRONT), pixels
  cv::Rect hand_box;                  //!< the hand square at the hand (empty for NONE)
  cv::Point2f shoulder_centre{0, 0};  //!< p_uc, pixels
  cv::Point2f body_centre{0, 0};      //!< p_bc, pixels
  cv::Rect2f user_box;                //!< the box p_uc, p_bc and the vector are measured on (UserView::box)
  std::string refused;                //!< why this frame gives no observation (not published; a counted
                                      //!< rejection), "" when observed
  std::optional<SkinDiagnostics> skin;
  std::optional<PoseDiagnostics> pose;
};

class HandMethod {
 public:
  virtual ~HandMethod() = default;
  // bgr: CV_8UC3. utime: the frame's capture time, microseconds (a method that smooths over time needs it).
  virtual HandsOutput observe(const cv::Mat& bgr, const UserView& user, int64_t utime) = 0;
  // Forgets the user and the scene (as a new track_id does).
  virtual void reset() = 0;
  // What the method runs on, for HEALTH ("skin model data/skin/skin_model.yaml").
  virtual std::string description() const = 0;
};

}  // namespace gpilot
