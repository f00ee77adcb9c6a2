// Parameters of the pose core (BlazePose on cv::dnn): the models, MediaPipe's published detection, ROI and
// smoothing constants (mediapipe/modules/pose_detection/pose_detection_cpu.pbtxt, pose_landmark/*.pbtxt), and
// ours for seeding from the tracker's user box. Not a config section of its own: the hands stage nests it.
#pragma once

#include <string>

#include "config_schema.hpp"

namespace gpilot {

// One Euro filter (Casiry, Roussel, Vogel, CHI 2012) as MediaPipe's LandmarksSmoothingCalculator runs it: the
// speed is measured in object sizes per second (value scale = 1 / object scale), so the same motion of a near
// and a far person is smoothed alike.
struct OneEuroParams {
  double min_cutoff = 0.1;       //!< Hz, cutoff at rest
  double beta = 40.0;            //!< cutoff gain per unit of speed (object sizes per second)
  double derivate_cutoff = 1.0;  //!< Hz, cutoff of the speed estimate

  template <class V>
  void visit(V& v) {
    v("min_cutoff", min_cutoff, 1e-6, 1000.0, "cutoff at rest, Hz (lower: smoother, more lag)");
    v("beta", beta, 0.0, 10000.0, "cutoff gain per unit speed, object sizes/s (higher: less lag when moving)");
    v("derivate_cutoff", derivate_cutoff, 1e-6, 1000.0, "cutoff of the speed estimate, Hz");
  }
};

// Landmark smoothing as pose_landmark_filtering.pbtxt: the 33 landmarks and, smoothed harder so the next crop
// stays still, the two auxiliary points the next ROI is made from. Ours: the auxiliary points' beta 5, not
// MediaPipe's 1 (the same at rest, a crop that follows a moving body 5 times sooner). With 1, a far figure's
// (9.7 m, a 74 px box) arm raised for UP outran its crop: its hand came to the crop's top edge, the landmark model
// read the arm folded, the folded arm kept the crop where it was, and UP was not flown for the whole gesture
// (1 of 10 e2e `far` runs; replayed from its log, beta 3 or more reads the arm OUT on 80 of 80 frames).
struct PoseSmoothingParams {
  bool enabled = true;
  OneEuroParams landmarks;                       //!< MediaPipe: 0.1 Hz, 40, 1 Hz
  OneEuroParams aux{0.01, 5.0, 1.0};             //!< MediaPipe: 0.01 Hz, 1, 1 Hz; beta ours (above)
  double visibility_alpha = 0.1;                 //!< low-pass weight of a new visibility (MediaPipe 0.1; 1 = off)
  double first_rate_hz = 30.0;                   //!< assumed frame rate until two frames give it (MediaPipe's default)

  template <class V>
  void visit(V& v) {
    v("enabled", enabled, "smooth landmarks over frames (One Euro, MediaPipe's pose_landmark_filtering)");
    v.group("landmarks", landmarks);
    v.group("aux", aux);
    v("visibility_alpha", visibility_alpha, 1e-6, 1.0, "low-pass weight of each new visibility/presence (1 = off; MediaPipe 0.1)");
    v("first_rate_hz", first_rate_hz, 1.0, 1000.0, "frame rate assumed until two frames give it, Hz");
  }
};

struct PoseParams {
  std::string model = "lite";             //!< landmark model: lite or full (README: speed)
  std::string models_dir = "models/pose";  //!< folder of the .onnx files, relative to the project root
  int threads = 1;                        //!< cv::dnn threads (process-wide: cv::setNumThreads)
  bool fast_depthwise = true;             //!< depthwise convs other than 3x3 on ours (depthwise_conv.hpp), not OpenCV's
  // Person detector (pose_detection_cpu.pbtxt and its calculators).
  double detector_score_threshold = 0.5;  //!< sigmoid score a detection needs (MediaPipe pose 0.5)
  double score_clipping = 100.0;          //!< raw score logits clipped to +-this before the sigmoid (MediaPipe 100)
  double nms_iou_threshold = 0.3;         //!< weighted NMS merges detections overlapping more (MediaPipe 0.3)
  // ROI (pose_detection_to_roi.pbtxt, pose_landmarks_to_roi.pbtxt): square of side 2 x |kp1 - kp0| x scale.
  double roi_scale = 1.25;                //!< MediaPipe 1.25
  double pose_flag_threshold = 0.5;       //!< pose flag below this: no pose, the detector runs next frame (MediaPipe 0.5)
  // Seeding from the tracker's user box (ours): the detector looks at the box grown by seed_margin (so it sees
  // the user whole, and no bystander beyond), and a tracked ROI whose centre (the hips) leaves the box grown by
  // track_margin hands over to the detector.
  double seed_margin = 0.25;              //!< detector region = user box grown by this share of its height, each side
  double track_margin = 0.25;             //!< tracked hips outside the user box grown by this share of its size: detect
  // Seeding from the user box: the landmark model runs on the ROIs of up to seed_candidates detections (hips in
  // the box, the body's centre line and size nearest the box's first; of several posed, the one whose landmarks'
  // bounding box overlaps the box most), and when none gives a pose (no detection in the box, or the pose flag
  // below the threshold) on the box's own ROI: upright, centred on the box, side box_roi_scale x its long side.
  // Development set (62 people), arm points within 0.1 of the box height: with a box ROI of 1.25 x the long side,
  // 1 candidate 86.8 %, 2 candidates 84.9 %; with 1 candidate, a box ROI of 1.0 / 1.25 x 87.4 / 86.8 % (94.9 %
  // within 0.2 both).
  int seed_candidates = 1;                //!< detections whose ROI the landmark model tries when seeding
  double box_roi_scale = 1.0;             //!< box ROI side / the user box's long side (0: no box ROI)
  // A tracked frame whose pose flag falls below the threshold (ours): the detector seeds the same frame (MediaPipe
  // loses it and seeds the next), and when the seed finds the pose the track corrects the auxiliary points' next
  // ROIs by what separates the seed's ROI from theirs. A body at the frame's edge: the aux points' ROI 16 px
  // below the detector's scored 0.4, the detector's 0.9, frame after frame; every other frame had no pose.
  bool reseed_in_frame = true;
  PoseSmoothingParams smoothing;

  template <class V>
  void visit(V& v) {
    v("model", model, "landmark model: lite or full");
    v("models_dir", models_dir, "folder of pose_detection.onnx and pose_landmark_<model>.onnx (relative: project root)");
    v("threads", threads, 1, 64, "cv::dnn threads (process-wide)");
    v("fast_depthwise", fast_depthwise, "depthwise convolutions other than 3x3 on gpilot's vectorised kernel (false: OpenCV 4.6's, unvectorised)");
    v("detector_score_threshold", detector_score_threshold, 0.0, 1.0, "person detector: score a detection needs (MediaPipe 0.5)");
    v("score_clipping", score_clipping, 1.0, 1000.0, "person detector: score logits clipped to +-this (MediaPipe 100)");
    v("nms_iou_threshold", nms_iou_threshold, 0.0, 1.0, "weighted NMS: detections overlapping more (IoU) are merged (MediaPipe 0.3)");
    v("roi_scale", roi_scale, 0.5, 4.0, "landmark crop side / twice the alignment distance (MediaPipe 1.25)");
    v("pose_flag_threshold", pose_flag_threshold, 0.0, 1.0, "pose flag below this: no pose, detect again (MediaPipe 0.5)");
    v("seed_margin", seed_margin, 0.0, 5.0, "detector region: user box grown by this share of its height each side");
    v("track_margin", track_margin, 0.0, 5.0, "tracked hip centre outside the user box grown by this share: detect again");
    v("seed_candidates", seed_candidates, 1, 10, "seeding: detections (hips in the user box) whose ROI the landmark model tries");
    v("box_roi_scale", box_roi_scale, 0.0, 4.0, "seeding: when no detection gives a pose, the user box's own ROI, side = this x its long side (0: none)");
    v("reseed_in_frame", reseed_in_frame, "a tracked frame without a pose is seeded again at once, and the track corrects its ROIs by the seed's (ours)");
    v.group("smoothing", smoothing);
  }
  void check(const ParamCheck& c) const { c.choice("model", model, {"lite", "full"}); }
};

}  // namespace gpilot
