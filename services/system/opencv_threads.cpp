#include "opencv_threads.hpp"

#include <climits>

#include <opencv2/core/utility.hpp>

#include "hands/hands_params.hpp"
#include "tracker/tracker_params.hpp"

namespace gpilot {

std::optional<int> opencv_threads_of(const Config& config, const std::string& stage) {
  if (stage == "tracker") return config.section<TrackerParams>("tracker").opencv_threads;
  if (stage == "hands") {
    const auto hands = config.section<HandsParams>("hands");
    if (hands.method == "pose") return hands.pose.threads;
  }
  return std::nullopt;
}

std::optional<int> fewest_opencv_threads(const std::vector<std::optional<int>>& asked) {
  const auto rank = [](int n) { return n < 0 ? INT_MAX : n; };  // -1: as many as the machine has
  std::optional<int> fewest;
  for (const std::optional<int>& n : asked)
    if (n && (!fewest || rank(*n) < rank(*fewest))) fewest = n;
  return fewest;
}

std::optional<int> set_opencv_threads(std::optional<int> n) {
  if (n) cv::setNumThreads(*n);
  return n;
}

}  // namespace gpilot
