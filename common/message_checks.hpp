// Structural checks every received message passes before a stage sees it: finite numbers, known enum
// values, consistent sizes. Each returns "" when the message is fine, else the reason it is rejected.
#pragma once

#include <string>

#include "gpilot/config_t.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/autopilot_t.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"

namespace gpilot {

// Bounds no camera, tracker or box of ours can pass: values beyond them are hostile or broken, and are
// rejected before any stage sizes a buffer or divides by them.
constexpr int kMaxImageSide = 16384;     //!< pixels, a side of any image (and of the image sizes messages name)
constexpr double kMinBoxSide = 1.0;      //!< pixels: a user box narrower or shorter than a pixel is no user
//! A user box spans at most this many image widths/heights, and its corner lies at most this many image sizes
//! off the image. Close up the body box passes the frame's edges: it is tracker.body_height_in_faces (7, at
//! most 20) face heights, and a face may fill the frame (the fuzzer made the tracker publish 4.6 image
//! heights on a 41 px frame), so the bound is the largest body box of the largest face, with margin.
constexpr double kMaxBoxInImages = 32.0;

std::string check_message(const image_t& m);
std::string check_message(const tracker_init_t& m);
std::string check_message(const user_track_t& m);
std::string check_message(const hand_obs_t& m);
std::string check_message(const gesture_cmd_t& m);
std::string check_message(const flight_control_t& m);
std::string check_message(const flight_setpoint_t& m);
std::string check_message(const vehicle_state_t& m);
std::string check_message(const autopilot_t& m);
std::string check_message(const ground_truth_t& m);
std::string check_message(const health_t& m);
std::string check_message(const config_t& m);

}  // namespace gpilot
