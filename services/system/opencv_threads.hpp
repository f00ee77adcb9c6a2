// OpenCV's worker threads (cv::setNumThreads) are the process's, not a stage's: a process sets them once, at
// start, before it builds a stage, from the settings of the stages it runs (tracker.opencv_threads;
// hands.pose.threads when hands.method is pose: the skin method has none and runs on OpenCV's default). No
// core and no service start function sets them, so one stage's setting never governs another's in a process
// that runs both (gpilot-replay --stage tracker,hands, gpilot-eval-hands --video).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "config.hpp"

namespace gpilot {

// The thread count `stage` (a config section name) asks for in `config`: tracker.opencv_threads,
// hands.pose.threads when hands.method is pose; nullopt for a stage without a setting.
std::optional<int> opencv_threads_of(const Config& config, const std::string& stage);

// For a process that runs several stages: the fewest any of them asks for (-1, OpenCV's default, counts as the
// most), so that none runs on more threads than it is budgeted on; nullopt when none asks.
std::optional<int> fewest_opencv_threads(const std::vector<std::optional<int>>& asked);

// cv::setNumThreads(*n) when n is set (else OpenCV's default stays); returns n.
std::optional<int> set_opencv_threads(std::optional<int> n);

}  // namespace gpilot
