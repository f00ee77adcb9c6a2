// SsdAnchorsCalculator's loop with pose_detection_cpu.pbtxt's options.
#include "ssd_anchors.hpp"

#include <cmath>

namespace gpilot {
namespace {

// pose_detection_cpu.pbtxt: SsdAnchorsCalculatorOptions.
constexpr int kInputSize = 224;
constexpr int kStrides[] = {8, 16, 32, 32, 32};
constexpr int kLayers = 5;
constexpr float kAnchorOffset = 0.5f;  //!< anchor at the cell centre
// min_scale 0.1484375 and max_scale 0.75 size the anchors only without fixed_anchor_size: not used here.

std::vector<SsdAnchor> make_anchors() {
  std::vector<SsdAnchor> anchors;
  int layer = 0;
  while (layer < kLayers) {
    // Layers of the same stride share one feature map; each adds an anchor of its scale (aspect ratio 1) and
    // one of the interpolated scale (aspect ratio 1, MediaPipe's default interpolated_scale_aspect_ratio).
    // With fixed_anchor_size every anchor is 1 x 1: only their count per cell matters.
    int per_cell = 0;
    int last = layer;
    while (last < kLayers && kStrides[last] == kStrides[layer]) {
      per_cell += 2;
      ++last;
    }
    const int cells = static_cast<int>(std::ceil(static_cast<float>(kInputSize) / static_cast<float>(kStrides[layer])));
    for (int y = 0; y < cells; ++y)
      for (int x = 0; x < cells; ++x)
        for (int a = 0; a < per_cell; ++a)
          anchors.push_back({(static_cast<float>(x) + kAnchorOffset) / static_cast<float>(cells),
                             (static_cast<float>(y) + kAnchorOffset) / static_cast<float>(cells), 1.0f, 1.0f});
    layer = last;
  }
  return anchors;
}

}  // namespace

const std::vector<SsdAnchor>& pose_detector_anchors() {
  static const std::vector<SsdAnchor> anchors = make_anchors();
  return anchors;
}

}  // namespace gpilot
