// gpilot-eval-hands --video: what a person in a real clip would make the drone do. The perception chain of the
// pipeline (tracker -> hands -> decide: the stages' cores through the same message conversions as their
// services, so the figures are the live stages') runs over every frame of a video file or an image folder (an
// OTB/UAV123 sequence's img/), offline and deterministic. With --gesture none (the person makes no gesture in the clip)
// every hand the stage reports is a false hand and every command but HOVER a false command: the hands issue's
// real-video bar ("a moving command on <= 20 % of frames where no gesture is made").
#pragma once

#include <string>

#include "config.hpp"

namespace gpilot {

struct VideoEvalOptions {
  std::string source;         //!< video file or image folder
  double fps = 25.0;          //!< image folders' frame rate (a video file has its own)
  std::string init_box;       //!< "x,y,w,h": the user's box on the first frame, as TRACKER_INIT gives it;
                              //!< "" = the tracker's face search, as live
  std::string gesture = "none";  //!< what the person does in the whole clip: "none" (no gesture)
  std::string csv_path;       //!< one line per frame ("" = none)
  std::string mp4_path;       //!< annotated video, the pipeline's overlay ("" = none)
  bool json = false;
};

// Prints the table (or one JSON object) on stdout; returns the exit status. Throws std::runtime_error for a
// source that cannot be read.
int run_video_eval(const VideoEvalOptions& options, const Config& config);

}  // namespace gpilot
