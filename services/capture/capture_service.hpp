// The capture loop on a bus (used by gpilot-capture and by its tests): opens the source, paces it, stamps
// seq and utime, and publishes CAMERA (and GROUND_TRUTH for the synthetic world). Reads VEHICLE_STATE for the
// synthetic camera's pose (closed loop). Writes HEALTH once a second (state and what source is open).
//
// utime (image_t and ground_truth_t, identical for one frame):
// - camera and synthetic world: the wall clock when the frame was grabbed / rendered (capture time);
// - video file and image folder: microseconds of media time, frame index / frame rate from the first frame
//   (continuing across --loop), so that replaying the same file gives the same utimes.
#pragma once

#include <cstdint>
#include <string>

#include "bus_node.hpp"
#include "config.hpp"

namespace gpilot {

struct CaptureOptions {
  enum class Kind { Synthetic, Video, Images, Camera };
  Kind kind = Kind::Synthetic;
  std::string source = "tour";   //!< scenario name or path, video file, image folder
  int camera_index = 0;
  bool loop = false;             //!< video / images: start again at the end
  bool as_fast_as_possible = false;  //!< files and synthetic world: no real-time pacing
  double duration_s = 0.0;       //!< stop after this much media/scenario time; 0 = no limit
  uint64_t seed = 1;             //!< synthetic world's seed (noise, shake)
};

// Runs until the source ends (exit status 0), --duration is reached (0), a stop signal (0), or the source
// cannot be opened (1, with the reason on stderr and in HEALTH). A camera that disappears is retried.
int run_capture(const Config& config, const CaptureOptions& options, BusNode& node);

}  // namespace gpilot
