// trajectory.png of gpilot-report, drawn with OpenCV on a white canvas (no plotting library at run time):
// the vehicle's path seen from above (north up, east right, equal scale), its altitude against time, and
// its horizontal distance to the user against time; every segment coloured by the gesture mode in force,
// with the user's position (GROUND_TRUTH person_position), axes, ticks, labels and a legend.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "run_summary.hpp"

namespace gpilot {

// BGR colour of a gesture mode on the plot (-1: before the first GESTURE_CMD).
cv::Scalar mode_colour(int mode);

// Tick values at 1, 2 or 5 x 10^k steps covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target);

cv::Mat draw_trajectory(const std::vector<TrajectoryPoint>& path, const std::string& title);

// Where a point of the path lands on the top view of draw_trajectory's canvas (for tests).
struct TopViewMapping {
  cv::Rect area;
  double east0, east1, north0, north1;
  cv::Point map(double north, double east) const;
};
TopViewMapping top_view_mapping(const std::vector<TrajectoryPoint>& path);

}  // namespace gpilot
