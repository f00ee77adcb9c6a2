// The trajectory plot: ticks, the path in its mode's colour where it should be, the user's marker.
#include <gtest/gtest.h>

#include "trajectory_plot.hpp"

namespace gpilot {
namespace {

TEST(NiceTicks, StepsOfOneTwoOrFive) {
  EXPECT_EQ(nice_ticks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(nice_ticks(-1.2, 3.7, 5), (std::vector<double>{-1, 0, 1, 2, 3}));
  const auto t = nice_ticks(0.0, 0.5, 5);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_NEAR(t[1], 0.1, 1e-12);
  EXPECT_TRUE(nice_ticks(1, 1, 5).empty());
}

std::vector<TrajectoryPoint> straight_north(int mode) {
  std::vector<TrajectoryPoint> path;
  for (int i = 0; i <= 20; ++i) {
    TrajectoryPoint p{};
    p.t_s = 0.1 * i;
    p.north = 0.5 * i;  // 0 .. 10 m north
    p.down = -2.0;
    p.mode = mode;
    p.has_person = true;
    p.person_north = 12.0;
    p.person_east = 3.0;
    path.push_back(p);
  }
  return path;
}

bool near_colour(const cv::Mat& img, cv::Point p, const cv::Scalar& c, int radius = 2) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const cv::Vec3b v = img.at<cv::Vec3b>(p.y + dy, p.x + dx);
      if (std::abs(v[0] - c[0]) < 8 && std::abs(v[1] - c[1]) < 8 && std::abs(v[2] - c[2]) < 8) return true;
    }
  return false;
}

TEST(TrajectoryPlot, PathIsDrawnInItsModeColourAtItsPlace) {
  const auto path = straight_north(gesture_cmd_t::MODE_FINE);
  const cv::Mat img = draw_trajectory(path, "test");
  ASSERT_EQ(img.type(), CV_8UC3);
  const TopViewMapping m = top_view_mapping(path);
  EXPECT_TRUE(near_colour(img, m.map(5.25, 0.0), mode_colour(gesture_cmd_t::MODE_FINE)));
  EXPECT_FALSE(near_colour(img, m.map(5.25, 1.5), mode_colour(gesture_cmd_t::MODE_FINE)));  // 1.5 m east: nothing
  // Equal scale: a metre north is as many pixels as a metre east.
  const cv::Point o = m.map(0, 0), n = m.map(1, 0), e = m.map(0, 1);
  EXPECT_NEAR(o.y - n.y, e.x - o.x, 1);
  EXPECT_GT(o.y, n.y);  // north is up
  // The user's marker is dark at the user's position.
  const cv::Vec3b u = img.at<cv::Vec3b>(m.map(12.0, 3.0));
  EXPECT_LT(u[0] + u[1] + u[2], 3 * 60);
}

TEST(TrajectoryPlot, SegmentsTakeTheColourOfTheirMode) {
  auto path = straight_north(gesture_cmd_t::MODE_HOVER);
  for (size_t i = 11; i < path.size(); ++i) path[i].mode = gesture_cmd_t::MODE_CLOSER;
  const cv::Mat img = draw_trajectory(path, "test");
  const TopViewMapping m = top_view_mapping(path);
  EXPECT_TRUE(near_colour(img, m.map(2.25, 0), mode_colour(gesture_cmd_t::MODE_HOVER)));
  EXPECT_TRUE(near_colour(img, m.map(8.25, 0), mode_colour(gesture_cmd_t::MODE_CLOSER)));
  EXPECT_FALSE(near_colour(img, m.map(8.25, 0), mode_colour(gesture_cmd_t::MODE_HOVER)));
}

TEST(TrajectoryPlot, EmptyAndSinglePointPathsStillDraw) {
  EXPECT_FALSE(draw_trajectory({}, "empty").empty());
  EXPECT_FALSE(draw_trajectory({straight_north(0)[0]}, "one").empty());
}

}  // namespace
}  // namespace gpilot
