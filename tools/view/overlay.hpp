// The drawing core of gpilot-view: one camera frame plus the messages of that frame (matched by seq) and
// the latest vehicle/health state in, one annotated image out. Pure: no LCM, no clock, no window.
//
// What is drawn follows the paper's figures, in red: the user box (USER_TRACK), the hand square
// (HAND_OBS), and the command of GESTURE_CMD from the shoulder centre p_uc (HAND_OBS): an arrow along the
// hand vector for FINE/UP/DOWN, a cross for CLOSER, a small circle for FURTHER. Ours: a thin red face box
// (USER_TRACK.face_box) on the frames where the tracker's cascade found the face, and the user's skeleton in thin
// cyan when the hands stage reads body landmarks (HAND_OBS of the pose method). A HUD strip under the
// image gives mode, buffer counts, track state, vehicle position/yaw and per-stage rates.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"
#include "pose/pose_landmarks.hpp"

namespace gpilot {

// The per-frame messages of one CAMERA frame (same seq); any may be missing.
struct FrameMessages {
  std::optional<user_track_t> track;
  std::optional<hand_obs_t> hand;
  std::optional<gesture_cmd_t> cmd;
  std::optional<ground_truth_t> truth;
};

// State that is not per frame: the latest of each as the frame is drawn.
struct HudState {
  std::optional<vehicle_state_t> vehicle;
  std::optional<flight_setpoint_t> setpoint;
  std::map<std::string, float> stage_hz;  // HEALTH name -> rate_out_hz
};

// Where a hands core can plug in a skin mask (CV_8UC1, frame size, non-zero = skin) for --skin-overlay.
using SkinMaskFn = std::function<cv::Mat(const cv::Mat& frame, const FrameMessages& msgs)>;

struct OverlayOptions {
  bool hud = true;            // the text strip under the image
  bool truth = false;         // GROUND_TRUTH in green: true box, hands, expected mode
  bool skin = false;          // --skin-overlay: HAND_OBS skin counts, and the mask when skin_mask is set
  SkinMaskFn skin_mask;       // empty until a hands core is linked in
};

// Colours (BGR) of the marks, so tests and docs agree with the drawing.
const cv::Scalar kMarkRed(0, 0, 255);
const cv::Scalar kLostAmber(0, 170, 255);
const cv::Scalar kTruthGreen(0, 200, 0);

// Rows of the HUD strip added under a frame of this size (0 when options.hud is false).
int hud_height(const cv::Size& frame, const OverlayOptions& options);

// frame: CV_8UC3 or CV_8UC1. Returns CV_8UC3: the frame with marks in its own pixel coordinates, and the
// HUD strip below it. The input is not modified.
cv::Mat draw_overlay(const cv::Mat& frame, int64_t seq, const FrameMessages& msgs, const HudState& hud,
                     const OverlayOptions& options);

// Where the command marks go (image pixels), or nothing when the frame's messages do not give them.
struct CommandMark {
  int8_t mode = gesture_cmd_t::MODE_HOVER;
  cv::Point2f origin;  // p_uc
  cv::Point2f tip;     // arrow end for FINE/UP/DOWN: p_uc + direction.xy * user_box_width
  float size = 0;      // half-size of the cross / radius of the circle, pixels
};
std::optional<CommandMark> command_mark(const FrameMessages& msgs);

const char* mode_name(int mode);            // "HOVER", "FINE", ... or "?"
const char* track_status_name(int status);  // "SEARCHING", "TRACKING", "LOST" or "?"

// Click-and-drag of a box in the viewer window, in image pixels. Pure, so it can be tested.
class BoxDrag {
 public:
  void press(int x, int y);
  void move(int x, int y);
  // The finished box (x, y, w, h) clipped to bounds, or nothing for a click without a real drag.
  std::optional<cv::Rect> release(int x, int y, const cv::Size& bounds);
  bool active() const { return active_; }
  cv::Rect current() const;

 private:
  bool active_ = false;
  cv::Point a_, b_;
};

}  // namespace gpilot
