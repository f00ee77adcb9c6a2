// The paper's range (issue 13): the paper finds the face to about 5 m and flies the user out to about 10 m.
// At which distance the synthetic user's face falls below what the cascade finds, and how small the body box
// and the hand are there (640x480, 60° field of view: f = 554 px).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <gtest/gtest.h>

#include "capture/synthetic_params.hpp"
#include "capture/synthetic_world.hpp"
#include "face_cascade.hpp"
#include "face_detector.hpp"
#include "image_codec.hpp"
#include "metrics.hpp"
#include "user_tracker.hpp"

namespace gpilot {
namespace {

struct AtDistance {
  double m;
  bool found;
  double face_px, truth_face_px, box_w, hand_px;
};

std::vector<AtDistance> faces_by_distance(const TrackerParams& tp) {
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::load("idle"), 1);
  FaceDetector faces(tp, load_face_cascade(tp));
  std::vector<AtDistance> out;
  for (double d = 3.0; d <= 10.01; d += 0.5) {
    const SyntheticFrame f = world.render(1.0, 25, CameraPose{3.0 - d, 0.0, -1.5, 0.0});
    // One whole scan of the frame (the search's own path, face.scan_slice_pixels a step), the first face found.
    std::optional<FaceDetection> face;
    faces.restart_scan();
    for (int t = faces.scan_tiles(f.bgr.size()); t > 0 && !face; --t) face = faces.scan_step(f.bgr);
    out.push_back({d, face.has_value(), face ? face->face.width : 0.0, f.truth.face_box.width, f.truth.user_box.width,
                   f.truth.hand_size});
  }
  return out;
}

// GIVEN the idle user seen from 3 to 10 m (every 0.5 m) WHEN the whole frame is scanned once THEN, searching the
// frame as it is (face.upscale 1), the face is found to 4.5 m (23 px) and not from 5 m (20.8 px, the cascade's
// 20 px window: min_face_px); with the default upscale 2 (faces below 20 px looked for in a copy enlarged
// twice) at every distance to 8 m (13 px), not at 8.5 m, again at 9 to 10 m (10.4 px). At 10 m the body box is
// 29 px wide and the hand 10 px.
TEST(TrackerRange, TheFaceIsFoundToFourAndAHalfMetresAsShotToNineAndAHalfEnlarged) {
  const auto farthest = [](const std::vector<AtDistance>& all) {  // found at every distance up to it
    double m = 0;
    for (const AtDistance& a : all) {
      if (!a.found) break;
      m = a.m;
    }
    return m;
  };
  TrackerParams as_shot;
  as_shot.face.upscale = 1.0;
  const std::vector<AtDistance> one = faces_by_distance(as_shot), two = faces_by_distance(TrackerParams{});
  for (size_t i = 0; i < one.size(); ++i)
    std::printf("%4.1f m: face %s as shot, %s enlarged (%.1f px; truth %.1f px), body box %.1f px wide, hand %.1f px\n",
                one[i].m, one[i].found ? "found" : "not found", two[i].found ? "found" : "not found", two[i].face_px,
                two[i].truth_face_px, two[i].box_w, two[i].hand_px);
  EXPECT_DOUBLE_EQ(farthest(one), 4.5);
  EXPECT_DOUBLE_EQ(farthest(two), 8.0);
  int found = 0;
  for (const AtDistance& a : two) found += a.found;
  EXPECT_EQ(found, 14);  // all but 8.5 m: found again at 9, 9.5 and 10 m (the cascade's window steps)
  for (const AtDistance& a : two) {
    if (!a.found) continue;
    EXPECT_NEAR(a.face_px / a.truth_face_px, 1.0, 0.15) << a.m << " m";
  }
}

// GIVEN the far scenario's user from 5 to 10 m, seen from five camera positions a few centimetres apart at each
// half metre, the frames as capture sends them (JPEG, quality 65, 4:4:4) WHEN the face re-check searches its window (where the user's box puts the face) THEN the window enlarged to
// make the face face.recheck_enlarged_face_px finds it nearly always, at its size; the upscale-2 copy alone
// (recheck_small_face_px 0) at the search's pyramid step misses many (far scenario's frames at 5-10 m: 122 of 210 found, 10-12 px faces 50
// of 133). A re-check that finds no face leaves a box the scale filter has let grow with a raised arm: 22 %
// too wide at 10 m in a CI run, and a hand pointing down read as inside the box.
TEST(TrackerRange, TheReCheckFindsAFarFaceInItsWindowEnlarged) {
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::load("far"), 1);
  const TrackerParams with;
  TrackerParams without;
  without.face.recheck_small_face_px = 0;
  without.face.recheck_scale_factor = without.face.scale_factor;  // the search's step: the re-check's finer one finds them all too
  FaceDetector enlarged(with, load_face_cascade(with)), as_before(without, load_face_cascade(without));
  int cases = 0, found = 0, found_before = 0;
  double worst_size = 0;
  for (double d = 5.0; d <= 10.01; d += 0.5)
    for (int k = 0; k < 5; ++k) {
      SyntheticFrame f = world.render(1.0, 25, CameraPose{5.0 - d, 0.013 * k, -1.5 + 0.011 * k, 0.0});
      ASSERT_EQ(image_to_mat(mat_to_image(f.bgr, 0, 0, image_t::PIXEL_FORMAT_JPEG, 65, JpegChroma::k444), f.bgr), "");
      const cv::Rect2d box(f.truth.user_box);
      const cv::Rect roi = face_recheck_window(box, with);
      const double expected = box.width / with.body().width_in_faces;
      const auto face = enlarged.recheck(f.bgr, roi, expected, with.face_recheck_min_share);
      const auto before = as_before.recheck(f.bgr, roi, expected, with.face_recheck_min_share);
      ++cases;
      found_before += before.has_value();
      if (!face) continue;
      ++found;
      worst_size = std::max(worst_size, std::abs(face->face.width / f.truth.face_box.width - 1.0));
    }
  std::printf("re-check at 5-10 m: face found in %d of %d windows enlarged, %d with the upscale-2 copy; worst size "
              "error %.0f %%\n", found, cases, found_before, 100 * worst_size);
  EXPECT_GE(found, cases - 2);
  EXPECT_LT(found_before, found - 10);
  EXPECT_LT(worst_size, 0.15);
}

// GIVEN the idle user 8 m from the still camera WHEN tracked from the first frame THEN the whole-frame scan
// (its last octave enlarged) finds them within one scan, and the track stays on them (IoU > 0.5).
TEST(TrackerRange, AUserAtEightMetresIsFoundByTheScanAndTracked) {
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::load("idle"), 1);
  const TrackerParams tp;
  UserTracker tracker(tp, load_tracker_models(tp));
  const int scan = FaceDetector(tp, load_face_cascade(tp)).scan_tiles(cv::Size(sp.width, sp.height));
  int found_at = -1;
  double worst = 1.0;
  for (int i = 0; i < scan + 100; ++i) {
    const SyntheticFrame f = world.render(i / sp.fps, i, CameraPose{-5.0, 0.0, -1.5, 0.0});
    const TrackOutput out = tracker.process(f.bgr);
    if (found_at < 0 && out.status == TrackStatus::kTracking) found_at = i;
    if (found_at >= 0) {
      ASSERT_EQ(out.status, TrackStatus::kTracking) << "frame " << i;
      worst = std::min(worst, iou(out.box, cv::Rect2d(f.truth.user_box)));
    }
  }
  std::printf("8 m: found at frame %d (a scan is %d tiles), worst IoU %.3f\n", found_at, scan, worst);
  ASSERT_GE(found_at, 0);
  EXPECT_LT(found_at, scan);
  EXPECT_GT(worst, 0.5);
}

// GIVEN the far scenario's user 5 m from a still camera, gesturing (open loop: the drone does not fly out), the
// track started by the tracker's own search WHEN it runs for 40 s THEN the box is never more than 12 % wider than
// the user, nor narrower (measured: 1.009 .. 1.105; 1.009 throughout since the re-check searches its window
// enlarged, face.recheck_small_face_px; a resize still takes one face's size, a step off). The cascade finds a 15 px face a 1.1 pyramid step larger or smaller from one re-check to the
// next; when a re-check that only had to move the box also took that face's size, the box grew to 66 px against
// the user's 57 (15 %) for seconds at a time, and every hand rule is a ratio of that width.
TEST(TrackerRange, AFarUsersBoxKeepsItsWidthThroughTheReChecks) {
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::load("far"), 1);
  UserTracker tracker{TrackerParams{}, load_tracker_models(TrackerParams{})};
  int tracked = 0;
  double widest = 0, narrowest = 10;
  for (int i = 0; i < 40 * sp.fps; ++i) {
    const SyntheticFrame f = world.render(i / sp.fps, i, std::nullopt);
    const TrackOutput out = tracker.process(f.bgr);
    if (out.status != TrackStatus::kTracking) continue;
    ++tracked;
    const double r = out.box.width / f.truth.user_box.width;
    widest = std::max(widest, r);
    narrowest = std::min(narrowest, r);
  }
  std::printf("far user at 5 m, %d frames tracked: box width %.3f .. %.3f of the user's\n", tracked, narrowest, widest);
  EXPECT_GT(tracked, 38 * sp.fps);
  EXPECT_LT(widest, 1.12);
  EXPECT_GT(narrowest, 0.95);
}

}  // namespace
}  // namespace gpilot
