// Wires the hands stage to a bus (see hands_service.cpp). The returned object holds the stage's state;
// keep it alive while the bus runs.
#pragma once

#include <memory>

#include "bus_node.hpp"
#include "config.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "hands/hand_method.hpp"
#include "image_codec_params.hpp"

namespace gpilot {

// One CAMERA frame and the USER_TRACK of the same seq through the stage (decode within limits, the sizes
// agree, the method): "" and the HAND_OBS to publish, or why the pair is rejected. The fuzz target uses it.
std::string hands_on_pair(HandMethod& method, const image_t& frame, const user_track_t& track,
                          const ImageLimits& limits, hand_obs_t& obs);
// The same in two steps, as the service takes them: the frame decoded when it arrives (while the tracker
// works on it: off the frame -> GESTURE_CMD path), observed when its track comes. decode_for_hands: "" and
// the BGR pixels, or why the frame cannot be observed; bgr's buffer is decoded into again when it is its own.
std::string decode_for_hands(const image_t& frame, const ImageLimits& limits, cv::Mat& bgr);
std::string hands_on_decoded(HandMethod& method, const image_t& frame, const cv::Mat& bgr, const user_track_t& track,
                             hand_obs_t& obs);

// The stage on node with the method hands.method names (make_hand_method), or with the one given.
std::shared_ptr<void> start_hands_service(const Config& config, BusNode& node);
std::shared_ptr<void> start_hands_service(const Config& config, BusNode& node, std::unique_ptr<HandMethod> method);

}  // namespace gpilot
