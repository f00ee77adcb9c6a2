// The user, not a bystander (issue 13): a look-alike (the same face) in other clothes who walks in front of the
// user and stands there must not take the track with them; the torso's colours tell them apart: the re-check
// finding their face where the box puts the user's makes the track LOST (not flown on), and the search while
// LOST refuses them and finds the user again once they have gone.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iterator>
#include <optional>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "body_fit.hpp"
#include "capture/synthetic_params.hpp"
#include "capture/synthetic_world.hpp"
#include "metrics.hpp"
#include "face_cascade.hpp"
#include "user_tracker.hpp"

namespace gpilot {
namespace {

// The user rests 3 m from the still camera; a walker in a red shirt comes in from the image's left at 1.6 m,
// stops in front of the user for 1.5 s (their head over the user's face: only theirs to see), then walks out
// to the right. (One who stands there longer than lost_search_frames, 2 s, is taken: once SEARCHING any face
// may be the user.)
const char* kStandsInFront = R"(
background: data/backgrounds/building.jpg
person: {north: 3.0, east: 0.0}
bystanders:
  - name: walker
    shirt_bgr: [40, 60, 170]
    keyframes:
      - {t: 0, north: 1.6, east: -2.6}
      - {t: 3, east: 0.0, transition_s: 2}
      - {t: 6.5, east: 2.6, transition_s: 2}
keyframes:
  - {t: 0, gesture: REST}
duration_s: 12
)";

struct Outcome {
  double iou_at_end = 0;     // with the user's true box, on the last frame
  int frames_elsewhere = 0;  // TRACKING with IoU < 0.2 after the walker has gone (from 10.5 s)
  int64_t other_faces = 0;
  int64_t off_user = 0;
};

// user_north: the user's distance from the camera (m); the walker's is 1.6 m. A control (min_torso_match 0) also
// runs without the re-check's step limit: limited, the walker's face, ~1.9 times the user's, moves the box a
// little at each re-check and the filter keeps the user without the torso check.
Outcome run(double min_torso_match, double user_north = 3.0, double min_window_side = DsstParams{}.min_window_side) {
  const SyntheticParams sp;
  std::string yaml = kStandsInFront;
  const std::string at = "north: 3.0";
  yaml.replace(yaml.find(at), at.size(), "north: " + std::to_string(user_north));
  const SyntheticWorld world(sp, Scenario::parse(yaml, "stands-in-front.yaml"), 1);
  TrackerParams tp;
  tp.recheck_min_torso_match = min_torso_match;
  tp.dsst.min_window_side = min_window_side;
  if (min_torso_match <= 0) tp.face_recheck_max_step = 0;
  UserTracker tracker(tp, load_tracker_models(tp));
  Outcome o;
  const int frames = static_cast<int>(world.scenario().duration_s() * sp.fps);
  for (int i = 0; i < frames; ++i) {
    const SyntheticFrame f = world.render(i / sp.fps, i, std::nullopt);
    const TrackOutput out = tracker.process(f.bgr);
    const double v = out.status == TrackStatus::kTracking ? iou(out.box, cv::Rect2d(f.truth.user_box)) : 0.0;
    if (i >= 10.5 * sp.fps && out.status == TrackStatus::kTracking && v < 0.2) ++o.frames_elsewhere;
    if (i == frames - 1) o.iou_at_end = v;
  }
  o.other_faces = tracker.other_faces();
  o.off_user = tracker.off_user();
  return o;
}

TEST(TrackerBystander, ALookAlikeStandingInFrontDoesNotTakeTheTrack) {
  // The control without the check runs the paper's window: the default's wider one (min_window_side) happens to
  // miss the walker's face at the re-check that took the track with the paper's, and keeps the user without it.
  const Outcome with = run(TrackerParams{}.recheck_min_torso_match), without = run(0.0, 3.0, 0.0);
  std::printf("look-alike in front: IoU at the end %.3f with the torso check (%lld faces not the user's), %.3f "
              "without; frames tracking elsewhere after %d / %d\n",
              with.iou_at_end, static_cast<long long>(with.other_faces), without.iou_at_end, with.frames_elsewhere,
              without.frames_elsewhere);
  EXPECT_GT(with.iou_at_end, 0.6);
  EXPECT_EQ(with.frames_elsewhere, 0);
  EXPECT_GT(with.other_faces, 0);
  // Without it the walker's face re-anchors the track on them and it leaves with them: the check is what holds.
  EXPECT_LT(without.iou_at_end, 0.2);
  EXPECT_EQ(without.other_faces, 0);
}

// The user 3.5 m away: the walker's face, at 1.6 m, is more than twice the user's, so the re-check does not
// take it for a face of theirs at all (it found no face of the user's size), while the filter, sure of the
// walker's shirt, followed them. The torso where the box puts the face is not in the user's clothes: the box
// is off the user, the track LOST (a CI run of scenario bystander flew 40 s on a wall after such a crossing).
// The control without the check runs the paper's window, as above: with the default's wider one the filter alone
// keeps the user at 3.3, 3.5 and 4.2 m and follows the walker at 3.8 (the check holds the user at all four).
TEST(TrackerBystander, ABoxOnNeitherTheUsersFaceNorTheirClothesIsLost) {
  const Outcome with = run(TrackerParams{}.recheck_min_torso_match, 3.5), without = run(0.0, 3.5, 0.0);
  std::printf("look-alike twice the user's size in front: IoU at the end %.3f with the torso check (%lld re-checks "
              "off the user), %.3f without; frames tracking elsewhere after %d / %d\n",
              with.iou_at_end, static_cast<long long>(with.off_user), without.iou_at_end, with.frames_elsewhere,
              without.frames_elsewhere);
  EXPECT_GT(with.iou_at_end, 0.6);
  EXPECT_EQ(with.frames_elsewhere, 0);
  EXPECT_GT(with.off_user, 0);
  EXPECT_LT(without.iou_at_end, 0.2);
  EXPECT_EQ(without.off_user, 0);
}

// The box left on the background: the user is gone from one frame to the next (the CI run's drone yawed
// to follow the box, which then held its place on the wall at PSR 20-39). A re-check finds no face there,
// and the filter is sure of itself; the torso where the box puts the face is wall, not the user's clothes.
TEST(TrackerBystander, ATrackLeftOnTheBackgroundIsLost) {
  const SyntheticParams sp;
  const char* kScene = R"(
background: data/backgrounds/building.jpg
person: {north: 3.0, east: %s}
keyframes:
  - {t: 0, gesture: REST}
duration_s: 10
)";
  char with_user[256], without_user[256];
  std::snprintf(with_user, sizeof with_user, kScene, "0.0");
  std::snprintf(without_user, sizeof without_user, kScene, "30.0");
  const SyntheticWorld user(sp, Scenario::parse(with_user, "user.yaml"), 1);
  const SyntheticWorld wall(sp, Scenario::parse(without_user, "wall.yaml"), 1);
  UserTracker tracker{TrackerParams{}, load_tracker_models(TrackerParams{})};
  int on_wall = 0;  // TRACKING frames without the user
  double psr_max = 0;
  for (int i = 0; i < 150; ++i) {
    const SyntheticFrame f = (i < 60 ? user : wall).render(i / sp.fps, i, std::nullopt);
    const TrackOutput out = tracker.process(f.bgr);
    if (i == 59) {
      ASSERT_EQ(out.status, TrackStatus::kTracking);
    }
    if (i >= 60 && out.status == TrackStatus::kTracking) {
      ++on_wall;
      psr_max = std::max(psr_max, out.confidence);
    }
  }
  std::printf("user gone: %d frames TRACKING on the wall, PSR up to %.1f; %lld re-checks off the user\n", on_wall,
              psr_max, static_cast<long long>(tracker.off_user()));
  // The first weak frame's early re-check drops it (without the torso test: three weak re-checks, 6 frames on it)
  EXPECT_LE(on_wall, 1);
  EXPECT_GT(tracker.off_user(), 0);
}

// The user, in a red shirt, walks slowly out of the image's left side (4 m in 4 s) and stays away. The filter
// follows them to the edge and can stay there on the wall, learning it; the re-check of a box whose face is not
// wholly in view comes after weak_recheck_frames (3), not a second later, and finds the wall's colours where
// the user's torso should be: LOST (a grey wall beside a blue-grey shirt matches it: the track holds the edge).
TEST(TrackerBystander, ABoxLeftOnTheImagesEdgeIsReCheckedWithinAFewFrames) {
  const char* kWalksOut = R"(
background: data/backgrounds/building.jpg
person: {north: 3.0, east: 0.0, shirt_bgr: [40, 60, 170]}
keyframes:
  - {t: 0, gesture: REST}
  - {t: 2, step_m: -4.0, transition_s: 4}
duration_s: 9
)";
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::parse(kWalksOut, "walks-out.yaml"), 1);
  auto tracking_while_out = [&](int weak_recheck_frames) {
    TrackerParams tp;
    tp.weak_recheck_frames = weak_recheck_frames;
    UserTracker tracker(tp, load_tracker_models(tp));
    int out_of_view = 0, tracking = 0;
    const int frames = static_cast<int>(world.scenario().duration_s() * sp.fps);
    for (int i = 0; i < frames; ++i) {
      const SyntheticFrame f = world.render(i / sp.fps, i, std::nullopt);
      const TrackOutput out = tracker.process(f.bgr);
      const cv::Rect2d user(f.truth.user_box);
      if (user.br().x > 0) continue;  // some of the user still in view
      ++out_of_view;
      if (out.status == TrackStatus::kTracking) ++tracking;
    }
    EXPECT_GT(out_of_view, 50);
    return tracking;
  };
  const int early = tracking_while_out(TrackerParams{}.weak_recheck_frames), late = tracking_while_out(1000);
  std::printf("user walked out of the side: TRACKING while they are out of view %d frames (re-checked a second "
              "apart: %d)\n", early, late);
  // Measured: 2 frames (the box holds the user's last strip until the re-check sees the wall) and 9; the control
  // fails the bound the early re-check meets.
  EXPECT_LE(early, 6);
  EXPECT_GT(late, 6);
}

// The user steps 4 m aside (out of view in 0.8 s) for 6 s while a look-alike in other clothes stands beside
// where they were. LOST at 2.4 s, SEARCHING from 4.4 s (lost_search_frames): a face there used to be taken as
// the user's, and the drone handed to the look-alike. For user_memory_frames (10 s) a face must still wear
// the user's clothes: the user is found again once back (9.4 s).
TEST(TrackerBystander, ALookAlikeIsNotTakenWhileTheUserIsAway) {
  const char* kAway = R"(
background: data/backgrounds/building.jpg
person: {north: 3.0, east: -0.4}
bystanders:
  - name: look-alike
    shirt_bgr: [40, 60, 170]
    keyframes:
      - {t: 0, north: 3.0, east: 0.9}
keyframes:
  - {t: 0, gesture: REST}
  - {t: 2, step_m: -4.0, transition_s: 0.8}
  - {t: 8, step_m: 0.0, transition_s: 0.8}
duration_s: 12
)";
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::parse(kAway, "away.yaml"), 1);
  struct Run {
    int on_other = 0;  // TRACKING while the user is out of view (from 2.6 s until they step back at 8 s)
    double iou_at_end = 0;
  };
  auto run_with = [&](int memory_frames) {
    TrackerParams tp;
    tp.user_memory_frames = memory_frames;
    UserTracker tracker(tp, load_tracker_models(tp));
    Run r;
    const int frames = static_cast<int>(world.scenario().duration_s() * sp.fps);
    for (int i = 0; i < frames; ++i) {
      const SyntheticFrame f = world.render(i / sp.fps, i, std::nullopt);
      const TrackOutput out = tracker.process(f.bgr);
      if (i >= 2.6 * sp.fps && i < 8.0 * sp.fps && out.status == TrackStatus::kTracking) ++r.on_other;
      if (i == frames - 1)
        r.iou_at_end = out.status == TrackStatus::kTracking ? iou(out.box, cv::Rect2d(f.truth.user_box)) : 0.0;
    }
    return r;
  };
  const Run with = run_with(TrackerParams{}.user_memory_frames), without = run_with(0);
  std::printf("user away 6 s beside a look-alike: TRACKING while away %d frames (without the memory %d); IoU "
              "with the user at the end %.3f (%.3f)\n",
              with.on_other, without.on_other, with.iou_at_end, without.iou_at_end);
  EXPECT_EQ(with.on_other, 0);
  EXPECT_GT(with.iou_at_end, 0.6);
  // Without it the look-alike is taken once SEARCHING, and kept after the user is back.
  EXPECT_GT(without.on_other, 25);
}

// A user lost to the walker and found again: the box before the walker came (frame 50, the walker still 1.5 m
// off to the side) and the first TRACKING output after the loss. edit: what the frames show once LOST.
struct ReFound {
  bool lost = false;
  int frame = -1;
  double width_before = 0;
  TrackOutput out;
  cv::Rect2d truth;
  double width_in_faces = 0;  // the track's body ratio when re-found
};

ReFound refind(const std::string& yaml, const std::function<void(SyntheticFrame&)>& edit = {}) {
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::parse(yaml, "refind.yaml"), 1);
  UserTracker tracker{TrackerParams{}, load_tracker_models(TrackerParams{})};
  ReFound r;
  const int frames = static_cast<int>(world.scenario().duration_s() * sp.fps);
  for (int i = 0; i < frames && r.frame < 0; ++i) {
    SyntheticFrame f = world.render(i / sp.fps, i, std::nullopt);
    if (r.lost && edit) edit(f);
    const TrackOutput out = tracker.process(f.bgr);
    if (i == 50) r.width_before = out.box.width;
    r.lost = r.lost || (i > 50 && out.status != TrackStatus::kTracking);
    if (r.lost && out.status == TrackStatus::kTracking) {
      r.frame = i;
      r.out = out;
      r.truth = cv::Rect2d(f.truth.user_box);
      r.width_in_faces = tracker.track_body().width_in_faces;
    }
  }
  return r;
}

// The user re-found with a walker still half over their body (a CI bystander run): the walker crosses in front
// (the track LOST on their face), then stops at 1.6 m covering the user's body on one side, the user's face in
// view. A body fitted to what shows then was 45 px wide against the user's 86, kept for the rest of the run,
// and the hands stage misread the arms; a known user (their clothes matched) keeps their build instead.
TEST(TrackerBystander, AUserReFoundHalfHiddenKeepsTheirBuild) {
  // The walker of kStandsInFront, who stops 0.25 m to the side instead of walking out.
  std::string yaml = kStandsInFront;
  const std::string walks_out = "{t: 6.5, east: 2.6, transition_s: 2}";
  yaml.replace(yaml.find(walks_out), walks_out.size(), "{t: 6, east: 0.25, transition_s: 0.5}");
  const ReFound r = refind(yaml);
  const double iou_after = iou(r.out.box, r.truth);
  std::printf("user re-found half hidden at frame %d: box %.0f px wide (%.0f before the walker came; a body fitted "
              "to what shows was 74), IoU with the user %.3f\n",
              r.frame, r.out.box.width, r.width_before, iou_after);
  ASSERT_TRUE(r.lost);
  ASSERT_GE(r.frame, static_cast<int>(6.5 * SyntheticParams{}.fps));  // found again with the walker standing half over them
  EXPECT_NEAR(r.out.box.width / r.width_before, 1.0, 0.05);
  EXPECT_GT(iou_after, 0.8);
}

// ... and keeps their clothes: re-found with the walker's red shirt over part of their torso, the track's
// clothes are blended with what shows, as a re-check blends them, not replaced by it. A CI bystander run replaced
// them at such a moment (match 0.62, above the gate's 0.5): once the walker had gone, the user's own shirt
// matched 0.45, the re-check took their face for someone else's, and the search refused them for the 10 s of
// user_memory_frames (that run's log, all its frames: 320 frames LOST before, 6 now). Here the walker stops
// 0.22 m to the user's side; the user's own torso is rendered without the walker on the same frame. (At 0.18 m
// the torso shows more of the walker's shirt than of the user's, matching the walker's 0.85 and the user's 0.54:
// not taken back while the walker stands there, recheck_other_clothes.)
TEST(TrackerBystander, AUserReFoundHalfHiddenKeepsTheirClothes) {
  std::string yaml = kStandsInFront;
  const std::string walks_out = "{t: 6.5, east: 2.6, transition_s: 2}";
  yaml.replace(yaml.find(walks_out), walks_out.size(), "{t: 6, east: 0.22, transition_s: 0.5}");
  std::string alone = yaml;
  const size_t from = alone.find("bystanders:"), to = alone.find("keyframes:\n  - {t: 0, gesture: REST}");
  alone.erase(from, to - from);
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::parse(yaml, "half-hidden.yaml"), 1), user_alone(sp, Scenario::parse(alone, "alone.yaml"), 1);
  const TrackerParams tp;
  UserTracker tracker(tp, load_tracker_models(tp));
  bool lost = false;
  for (int i = 0; i < static_cast<int>(world.scenario().duration_s() * sp.fps); ++i) {
    const SyntheticFrame f = world.render(i / sp.fps, i, std::nullopt);
    const TrackOutput out = tracker.process(f.bgr);
    lost = lost || (i > 50 && out.status != TrackStatus::kTracking);
    if (!lost || out.status != TrackStatus::kTracking) continue;
    ASSERT_TRUE(out.face.has_value());
    const SyntheticFrame clean = user_alone.render(i / sp.fps, i, std::nullopt);
    const auto own = torso_colours(clean.bgr, cv::Rect2d(clean.truth.face_box), tp.body_fit, tp.torso_colour_bins, tp.torso_dark_level);
    const auto shown = torso_colours(f.bgr, *out.face, tp.body_fit, tp.torso_colour_bins, tp.torso_dark_level);
    const double kept = colour_match(tracker.user_clothes(), own), replaced = colour_match(shown, own);
    std::printf("user re-found half hidden at frame %d: the track's clothes match the user's own shirt %.3f (what "
                "showed: %.3f)\n", i, kept, replaced);
    ASSERT_GE(i, static_cast<int>(6.5 * sp.fps));  // with the walker standing over part of them
    EXPECT_LT(replaced, 0.85);                     // the shirt that showed was in part the walker's
    EXPECT_GT(kept, 0.9);
    return;
  }
  FAIL() << "the user was not lost and found again";
}

// The user re-found on a part of their face (a CI bystander run: the scan's pyramid found a 22 px face inside the
// user's 36 px one, and a body box from it was 62 px wide for their 90): a known user's face much smaller than
// their last one is taken at the last one's size. Here, once the walker has covered the user's face (LOST), the
// user's face is shown at 0.6 of its size on their unchanged body: what the cascade then finds is the part.
TEST(TrackerBystander, AUserReFoundOnAPartOfTheirFaceKeepsTheirSize) {
  const ReFound r = refind(kStandsInFront, [](SyntheticFrame& f) {
    // The face box shrunk to 0.6 about its centre; the ring around it filled with the face box's edge colour.
    const cv::Rect face = cv::Rect(f.truth.face_box) & cv::Rect(0, 0, f.bgr.cols, f.bgr.rows);
    cv::Mat region = f.bgr(face);
    cv::Mat part;
    cv::resize(region, part, cv::Size(), 0.6, 0.6, cv::INTER_AREA);
    region.setTo(cv::mean(region.row(0)));
    part.copyTo(region(cv::Rect((face.width - part.cols) / 2, (face.height - part.rows) / 2, part.cols, part.rows)));
  });
  const double small_face = r.out.face ? r.out.face->width : 0.0;
  std::printf("user re-found on a face 0.6 of theirs at frame %d: face %.0f px, box %.0f px wide (%.0f before)\n",
              r.frame, small_face, r.out.box.width, r.width_before);
  ASSERT_TRUE(r.lost);
  ASSERT_GT(r.frame, 0);
  const double last_face = r.width_before / r.width_in_faces;
  ASSERT_GT(small_face, 0.0);
  ASSERT_LT(small_face, 0.8 * last_face) << "the part was not what was found (last face " << last_face << " px)";
  EXPECT_NEAR(r.out.box.width / r.width_before, 1.0, 0.1);
}

// Scenario bystander as the drone flew it in an e2e run: the look-alike walker crosses between user and drone
// twice (10-14 s, and 21.5-25.5 s while the user points and the drone slides 1.3 m sideways, turning 17 deg).
// The camera path is that run's (every 0.5 s, linear between; a hover's 0.3 deg of yaw wobble on top), and 30 % of
// the frames are skipped at random, as a loaded machine's tracker skips them. Returns the longest run of frames
// TRACKING off the user (IoU < 0.3) from 8 s on: the drone turns after the box while it lasts.
int longest_drag(const TrackerParams& tp, unsigned drop_pattern) {
  struct Pose {
    double t, north, east, down, yaw;
  };
  static const Pose kPath[] = {
      {0.0, 0.000, 0.000, -1.500, 0.000},   {5.0, 0.000, 0.000, -1.500, 0.000},   {5.5, 0.000, -0.063, -1.502, 0.000},
      {6.0, 0.000, -0.238, -1.508, 0.003},  {6.5, 0.002, -0.440, -1.515, 0.061},  {7.0, 0.015, -0.653, -1.524, 0.132},
      {7.5, 0.043, -0.866, -1.535, 0.203},  {8.0, 0.085, -1.081, -1.546, 0.273},  {8.5, 0.142, -1.290, -1.555, 0.342},
      {9.0, 0.198, -1.458, -1.550, 0.411},  {9.5, 0.213, -1.500, -1.548, 0.447},  {10.0, 0.216, -1.507, -1.547, 0.448},
      {10.5, 0.216, -1.509, -1.547, 0.449}, {15.0, 0.216, -1.509, -1.547, 0.449}, {15.5, 0.192, -1.460, -1.549, 0.449},
      {16.0, 0.121, -1.312, -1.554, 0.449}, {16.5, 0.043, -1.150, -1.560, 0.443}, {17.0, -0.035, -0.982, -1.566, 0.388},
      {17.5, -0.108, -0.805, -1.569, 0.327}, {18.0, -0.171, -0.620, -1.572, 0.267}, {18.5, -0.227, -0.421, -1.575, 0.204},
      {19.0, -0.264, -0.255, -1.568, 0.141}, {19.5, -0.273, -0.214, -1.566, 0.114}, {20.0, -0.274, -0.207, -1.565, 0.113},
      {20.5, -0.275, -0.205, -1.565, 0.113}, {22.0, -0.275, -0.205, -1.565, 0.113}, {22.5, -0.267, -0.277, -1.568, 0.113},
      {23.0, -0.244, -0.472, -1.576, 0.113}, {23.5, -0.221, -0.679, -1.585, 0.127}, {24.0, -0.196, -0.874, -1.596, 0.161},
      {24.5, -0.186, -0.938, -1.599, 0.223}, {25.0, -0.155, -1.074, -1.603, 0.256}, {25.5, -0.103, -1.267, -1.609, 0.312},
      {26.0, -0.054, -1.428, -1.603, 0.374}, {26.5, -0.041, -1.467, -1.601, 0.401}, {27.0, -0.039, -1.474, -1.601, 0.402}};
  const SyntheticParams sp;
  const SyntheticWorld world(sp, Scenario::load("bystander"), 1);
  UserTracker tracker(tp, load_tracker_models(tp));
  std::mt19937 rng(drop_pattern);
  int run = 0, longest = 0;
  for (int i = 0; i < static_cast<int>(27.0 * sp.fps); ++i) {
    if (i > 4 * sp.fps && rng() % 10 < 3) continue;
    const double t = i / sp.fps;
    size_t k = 0;
    while (k + 2 < std::size(kPath) && kPath[k + 1].t <= t) ++k;
    const Pose &a = kPath[k], &b = kPath[k + 1];
    const double w = std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0);
    const auto mix = [w](double x, double y) { return x + w * (y - x); };
    const double wobble = 0.3 * CV_PI / 180 * std::sin(2.1 * t + drop_pattern);
    const SyntheticFrame f =
        world.render(t, i, CameraPose{mix(a.north, b.north), mix(a.east, b.east), mix(a.down, b.down), mix(a.yaw, b.yaw) + wobble});
    const TrackOutput out = tracker.process(f.bgr);
    const bool off = i > 8 * sp.fps && out.status == TrackStatus::kTracking && iou(out.box, cv::Rect2d(f.truth.user_box)) < 0.3;
    run = off ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest;
}

// recheck_other_clothes: after the first crossing the track knows the walker's shirt; on the second a torso
// showing more of it than of the user's is the walker's. Measured on 24 drop patterns: without the rule one took
// the box 4 frames; with it none (on a second bench, each camera pose held for the log's 8 ms steps and 36
// patterns: 6 took it 1-6 frames without, 2 took it 3 frames with). Since the re-check measures faces at its finer
// pyramid step (face.recheck_scale_factor), the 12 patterns here: without the rule one took it 2 frames, with it none.
TEST(TrackerBystander, AWalkerCrossingWhileTheDroneMovesDoesNotTakeTheBox) {
  TrackerParams without;
  without.recheck_other_clothes = false;
  int with_max = 0, without_max = 0;
  for (unsigned pattern = 1; pattern <= 12; ++pattern) {
    const int a = longest_drag(TrackerParams{}, pattern), b = longest_drag(without, pattern);
    std::printf("drop pattern %u: longest run TRACKING off the user %d frames (without recheck_other_clothes: %d)\n",
                pattern, a, b);
    with_max = std::max(with_max, a);
    without_max = std::max(without_max, b);
  }
  EXPECT_EQ(with_max, 0);
  EXPECT_GE(without_max, 2);
}

// torso_colours: chromaticity, so a gain on the light leaves it; another shirt does not match.
TEST(TorsoColours, LightGainKeepsThemAnotherShirtDoesNot) {
  cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(120, 120, 120));
  const cv::Rect2d face(140, 40, 40, 40);
  frame(cv::Rect(130, 90, 60, 100)).setTo(cv::Scalar(150, 82, 40));  // blue shirt under the face
  for (int y = 95; y < 190; y += 10) frame(cv::Rect(130, y, 60, 3)).setTo(cv::Scalar(82, 45, 22));  // darker stripes
  const BodyFitParams bp;
  const auto blue = torso_colours(frame, face, bp, 8, 20.0);
  ASSERT_EQ(blue.size(), 64u);
  cv::Mat dim;
  frame.convertTo(dim, -1, 0.6);
  EXPECT_GT(colour_match(blue, torso_colours(dim, face, bp, 8, 20.0)), 0.95);
  cv::Mat red = frame.clone();
  red(cv::Rect(130, 90, 60, 100)).setTo(cv::Scalar(40, 60, 170));
  EXPECT_LT(colour_match(blue, torso_colours(red, face, bp, 8, 20.0)), 0.2);
  cv::Mat grey;
  cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
  EXPECT_TRUE(torso_colours(grey, face, bp, 8, 20.0).empty());
  EXPECT_DOUBLE_EQ(colour_match(blue, {}), -1.0);
}

}  // namespace
}  // namespace gpilot
