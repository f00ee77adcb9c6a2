// gpilot-eval-hands --video: what a person in a real clip would make the drone do. The perception chain of the
// pipeline (tracker -> hands -> decide: the stages' cores through the same message conversions as their
// services, so the figures are the live stages') runs over every frame of a video file or an image folder (an
// OTB/UAV123 sequence's img/), offline and deterministic, and is judged against what the person does: the whole
// clip (--gesture none: no gesture) or frame ranges (--truth FILE: "first,last,GESTURE" lines, 0-based and
// inclusive, GESTURE one of REST OUT UP DOWN CLOSER FURTHER; frames outside every range are not judged).
// The hands issue's real-video bars: the right hand observation (REST: none; OUT, UP, DOWN: OUT; CLOSER /
// FURTHER: FRONT higher / lower) on >= 80 % of gesture frames, a moving command on <= 20 % of frames where no
// gesture is made. Frames within settle_s of the clip's start or of a change of gesture are not judged (the
// stage and the decision need that long: the e2e tests judge from 0.8 s after each change).
#pragma once

#include <string>

#include "config.hpp"

namespace gpilot {

struct VideoEvalOptions {
  std::string source;         //!< video file or image folder
  double fps = 25.0;          //!< image folders' frame rate (a video file has its own)
  std::string init_box;       //!< "x,y,w,h": the user's box on the first frame, as TRACKER_INIT gives it;
                              //!< "" = the tracker's face search, as live
  std::string gesture = "none";  //!< what the person does in the whole clip: "none" (no gesture), unless truth_path
  std::string truth_path;        //!< per-frame-range gesture truth ("" = gesture for the whole clip)
  double settle_s = 0.8;         //!< frames this soon after the start or a change of gesture are not judged
  std::string csv_path;       //!< one line per frame ("" = none)
  std::string mp4_path;       //!< annotated video, the pipeline's overlay ("" = none)
  bool json = false;
};

// Prints the table (or one JSON object) on stdout; returns the exit status. Throws std::runtime_error for a
// source that cannot be read.
int run_video_eval(const VideoEvalOptions& options, const Config& config);

}  // namespace gpilot
