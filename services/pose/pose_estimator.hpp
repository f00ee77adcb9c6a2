// The pose core's public class: BlazePose's 33 body landmarks of the tracked user, frame by frame, tracked as
// MediaPipe's pose_landmark graph does (each frame's ROI from the previous frame's auxiliary points; the person
// detector only to start and when the track is lost) and seeded by the tracker's user box, so the pose is the
// user's and never a bystander's. No clock, no bus: the same frames, boxes and utimes give the same landmarks,
// bit for bit.
//
//   PoseEstimator pose(params, PoseModels::load(params));   // PoseModelError: a model file missing or wrong
//   PoseResult r = pose.estimate(frame_bgr, user_box, utime);
//   if (r.found) use(r.landmarks);                           // frame pixels
#pragma once

#include <cstdint>
#include <optional>

#include <opencv2/core.hpp>

#include "landmark_model.hpp"
#include "landmark_smoothing.hpp"
#include "person_detector.hpp"
#include "pose_landmarks.hpp"
#include "pose_models.hpp"
#include "pose_params.hpp"
#include "pose_roi.hpp"

namespace gpilot {

struct PoseCounters {
  int64_t detector_runs = 0;      //!< frames the person detector ran on
  int64_t frames_tracked = 0;     //!< frames whose ROI came from the previous frame's landmarks
  int64_t nonfinite_outputs = 0;  //!< frames a net gave NaN/Inf on (no pose that frame)
  int64_t reseeds = 0;            //!< tracked frames without a pose seeded again in the same frame (reseed_in_frame)
  int64_t reseeds_found = 0;      //!< ... of which the seed found the pose
};

struct PoseResult {
  bool found = false;             //!< false: no pose this frame (landmarks all zero)
  float pose_flag = 0;            //!< the landmark model's pose probability (0 when it did not run)
  PoseLandmarks landmarks{};      //!< frame pixels, smoothed
  PoseRoi roi;                    //!< the ROI the landmark model saw (size 0 when it did not run)
  bool detector_ran = false;      //!< the person detector ran this frame
  bool nonfinite = false;         //!< a net gave NaN/Inf this frame (counted in counters.nonfinite_outputs)
  PoseCounters counters;          //!< totals since construction
};

class PoseEstimator {
 public:
  // params.threads is not set here: OpenCV's thread count is the process's (services/system/opencv_threads.hpp).
  PoseEstimator(const PoseParams& params, PoseModels models);

  // The user's pose in bgr (CV_8UC3, not empty: else std::invalid_argument). user_box: the tracker's box of the
  // user, frame pixels; the detector looks only around it and a track whose hips leave it is dropped. An empty
  // box (no area) means the whole frame (the best-scoring person). utime: the frame's time, microseconds
  // (smoothing; frames in increasing order).
  PoseResult estimate(const cv::Mat& bgr, const cv::Rect2f& user_box, int64_t utime);

  // Forgets the track and the smoothing: the next frame starts from the detector.
  void reset();

  const PoseCounters& counters() const { return counters_; }

 private:
  struct Seed {
    PoseRoi roi;
    LandmarkOutput out;
  };
  // The detector, then the landmark model on the candidate ROIs; nullopt when no pose is found.
  std::optional<Seed> seed(const cv::Mat& bgr, const cv::Rect2f& user_box, bool& nonfinite);
  PoseResult lost(PoseResult r);

  PoseParams params_;
  PersonDetector detector_;
  LandmarkModel landmark_;
  LandmarkSmoothing smoothing_;
  std::optional<PoseRoi> next_roi_;  // from this frame's auxiliary points, corrected by roi_correction_
  PoseRoi aux_roi_;                  // next_roi_ as the auxiliary points give it
  // What the track changes in the auxiliary points' ROI (reseed_in_frame): the seed's ROI that found the pose
  // against the one they gave, which did not.
  struct RoiCorrection {
    cv::Point2f shift;     //!< pixels
    float scale = 1;       //!< size ratio
    float turn = 0;        //!< radians
  } roi_correction_;
  PoseCounters counters_;
};

// The detections that may be the user's, best match first: those whose hip centre lies in user_box (the
// tracker's box reaches from the head to the knees: the user's hips are in it), ordered by how far the body's
// centre line (hip centre to the full-body scale point) is from the box's, in box widths, plus how far the
// body's size (twice the alignment distance) is from the box height (|log| of their ratio): of two people in one
// box, the one the box is drawn around. At most max_count. An empty user_box: the detections as given (best
// score first).
std::vector<PersonDetection> user_detection_candidates(const std::vector<PersonDetection>& detections,
                                                       const cv::Rect2f& user_box, size_t max_count);

// The first of user_detection_candidates; nullopt when there is none.
std::optional<PersonDetection> choose_user_detection(const std::vector<PersonDetection>& detections,
                                                     const cv::Rect2f& user_box);

// The user box's own ROI: upright, centred on the box, side scale x its long side.
PoseRoi box_roi(const cv::Rect2f& user_box, float scale);

// How well a pose matches the user box: IoU of the bounding box of its 33 landmarks with user_box.
double landmarks_box_iou(const PoseLandmarks& landmarks, const cv::Rect2f& user_box);

// r grown by share x its width on the left and right and share x its height above and below.
cv::Rect2f grow_box(const cv::Rect2f& r, float share);

}  // namespace gpilot
