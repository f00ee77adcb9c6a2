// The tracker on the synthetic world's `tour` (every gesture of the paper in turn, 60 s at 25 fps, arms
// stretched out of the body box and back): found by the face search on the first frames, then the box stays
// on the person throughout, never LOST.
#include <cstdio>
#include <optional>

#include <gtest/gtest.h>

#include "capture/synthetic_params.hpp"
#include "capture/synthetic_world.hpp"
#include "metrics.hpp"
#include "user_tracker.hpp"

namespace gpilot {
namespace {

TEST(TrackerTour, BoxStaysOnThePersonThroughout) {
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::load("tour"), 1);
  const TrackerParams tp;
  UserTracker tracker(tp);
  const int frames = static_cast<int>(world.scenario().duration_s() * sp.fps);
  int found_at = -1, worst_frame = -1;
  double worst_iou = 1.0;
  for (int i = 0; i < frames; ++i) {
    const SyntheticFrame f = world.render(i / sp.fps, i, std::nullopt);
    const TrackOutput out = tracker.process(f.bgr);
    if (found_at < 0) {
      if (out.status == TrackStatus::kTracking) found_at = i;
      continue;
    }
    ASSERT_EQ(out.status, TrackStatus::kTracking) << "frame " << i << " psr " << out.confidence;
    ASSERT_EQ(out.track_id, 1) << "frame " << i;
    const double v = iou(out.box, cv::Rect2d(f.truth.user_box));
    if (v < worst_iou) {
      worst_iou = v;
      worst_frame = i;
    }
  }
  std::printf("tour: found at frame %d, worst IoU %.3f at frame %d of %d\n", found_at, worst_iou, worst_frame, frames);
  EXPECT_GE(found_at, 0);
  EXPECT_LE(found_at, 2) << "the face search should find the user at once";
  EXPECT_EQ(tracker.last().init, InitSource::kFace);
  // The box is the body box a perfect tracker reports (head-body ratio of the true face box).
  EXPECT_GT(worst_iou, 0.6) << "worst at frame " << worst_frame;
}

}  // namespace
}  // namespace gpilot
