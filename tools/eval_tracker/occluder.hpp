// An occluder painted over a sequence's frames: a bench for a target partly hidden (a parked car over the
// legs, a pole the walker passes behind), which the shared clips do not have. The same pixels for every
// tracker under test; the truth is not changed (the target is still there, behind).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sequence.hpp"

namespace gpilot {

struct Occluder {
  cv::Rect rect;       //!< frame pixels (clipped to each frame)
  int first = 1;       //!< first frame painted, 1-based
  int last = 0;        //!< last frame painted, 1-based; 0: to the end
};

// "x,y,w,h" or "x,y,w,h@first-last" (frames 1-based, inclusive; "first-" to the end). None if malformed,
// w or h <= 0, first < 1 or last < first.
std::optional<Occluder> parse_occluder(const std::string& spec);

// src's frames with every occluder whose frames include theirs filled with texture (CV_8UC3 BGR, resized to the
// rectangle as given, then clipped with it; empty: mid grey; in grey on a one-channel frame). Throws
// std::invalid_argument for no src or a texture that is not CV_8UC3.
std::unique_ptr<FrameSource> occluded(std::unique_ptr<FrameSource> src, std::vector<Occluder> occluders, const cv::Mat& texture);

}  // namespace gpilot
