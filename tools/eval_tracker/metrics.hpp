// OTB measures of a tracker's boxes against ground truth: success curve (fraction of frames with IoU above
// each threshold 0, 0.05 .. 1) and its area (AUC), precision at 20 px centre error, mean IoU; and the
// success plot as a PNG.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "box_iou.hpp"

namespace gpilot {

double centre_error(const cv::Rect2d& a, const cv::Rect2d& b);

struct TrackScores {
  std::vector<double> success;  //!< 21 rates at IoU thresholds 0, 0.05, .., 1 (OTB: IoU > threshold)
  double success_auc = 0;       //!< mean of success, as OTB
  double precision_20px = 0;    //!< fraction of frames with centre error <= 20 px
  double mean_iou = 0;
  int frames = 0;               //!< frames with ground truth
};

// ious and errors: one per frame with ground truth (a frame without a box: IoU 0, error infinite).
TrackScores score(const std::vector<double>& ious, const std::vector<double>& errors);

// How a tracker behaved where the truth says the target is not visible (UAV123's NaN frames): these frames
// are not scored; what counts there is whether the tracker said so and whether it found the target again.
struct FrameVerdict {
  bool absent = false;    //!< the truth marks the target as not visible
  bool reported = false;  //!< the tracker gave a box (false: it reported the target lost)
  double iou = 0.0;       //!< IoU with the truth on a visible frame (the last box when none was reported)
};
struct AbsenceBehaviour {
  int absent_frames = 0;
  int reported_lost = 0;            //!< absent frames on which the tracker reported no box
  //! Per reappearance (an absent run followed by a visible frame): visible frames until the first with
  //! IoU >= refound_iou counting from 0 (0: on the first visible frame), -1 if never before the end.
  std::vector<int> refound_after;
};
AbsenceBehaviour absence_behaviour(const std::vector<FrameVerdict>& frames, double refound_iou = 0.5);

struct PlotCurve {
  std::string label;
  std::vector<double> success;
};
// Writes a success plot (rate against IoU threshold) to path; throws std::runtime_error if it cannot.
void write_success_plot(const std::string& path, const std::string& title, const std::vector<PlotCurve>& curves);

}  // namespace gpilot
