// Frame sources of gpilot-eval-tracker: an OTB folder (img/*.jpg + groundtruth_rect.txt, 1-based x,y,w,h;
// or init_rect.txt, 0-based, first frame only) or an LCM log (CAMERA paired with GROUND_TRUTH by seq).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>
#include <opencv2/core.hpp>

namespace gpilot {

struct EvalFrame {
  cv::Mat image;                    //!< BGR
  std::optional<cv::Rect2d> truth;  //!< 0-based x, y, w, h, pixels; none where the sequence has none
  //! The truth says the target is not visible in this frame (UAV123's "NaN,NaN,NaN,NaN" line): the frame is
  //! left out of the scores, as UAV123's toolkit does, and the tracker's behaviour there reported apart.
  bool absent = false;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // False at the end. Throws std::runtime_error for a file that cannot be read.
  virtual bool next(EvalFrame& out) = 0;
  virtual std::string name() const = 0;
};

// Throws std::runtime_error when the folder has no img/*.jpg or no box file, or a box line is malformed.
std::unique_ptr<FrameSource> open_otb(const std::string& dir);
// Throws std::runtime_error when the log cannot be opened.
std::unique_ptr<FrameSource> open_lcm_log(const std::string& path);

#ifdef GPILOT_HAVE_SYNTHETIC
// The synthetic world's scenario (name or .yaml path) at the capture defaults, truth = its user_box, or its
// face_box (kFace: a head annotated as OTB's face clips are; frames without a face are absent).
enum class SyntheticTruthBox { kUserBox, kFace };
std::unique_ptr<FrameSource> open_synthetic(const std::string& scenario, SyntheticTruthBox truth = SyntheticTruthBox::kUserBox);
#endif

// "x,y,w,h" (commas, tabs or spaces); none if malformed or w, h <= 0.
std::optional<cv::Rect2d> parse_box(const std::string& line);
// True for UAV123's line of a frame without a visible target: four fields, all NaN.
bool is_absent_line(const std::string& line);

}  // namespace gpilot
