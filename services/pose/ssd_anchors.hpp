// The SSD anchors of BlazePose's person detector, as MediaPipe's SsdAnchorsCalculator makes them from
// pose_detection_cpu.pbtxt's options: 5 layers, strides 8, 16, 32, 32, 32 on a 224x224 input, aspect ratio 1
// plus the interpolated scale, fixed anchor size: 28x28x2 + 14x14x2 + 7x7x6 = 2254 anchors.
#pragma once

#include <vector>

namespace gpilot {

struct SsdAnchor {
  float x_center = 0;  //!< 0..1 of the input width
  float y_center = 0;  //!< 0..1 of the input height
  float width = 1;     //!< 0..1 (1: fixed anchor size)
  float height = 1;
};

// The detector's anchors, in the order of its output rows (layer, then row, column, anchor).
const std::vector<SsdAnchor>& pose_detector_anchors();

}  // namespace gpilot
