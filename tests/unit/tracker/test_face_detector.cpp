// The Haar face search and the head-body ratio on real photographs (data/people, see data/README.md).
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "face_cascade.hpp"
#include "face_detector.hpp"

namespace gpilot {
namespace {

cv::Mat photo(const std::string& name) {
  const std::string path = std::string(GPILOT_SOURCE_DIR) + "/data/people/" + name;
  cv::Mat m = cv::imread(path, cv::IMREAD_COLOR);
  EXPECT_FALSE(m.empty()) << path;
  return m;
}

bool contains(const cv::Rect2d& box, cv::Point2d p) { return box.contains(p); }

TEST(BodyFromFace, UsesTheHeadBodyRatios) {
  TrackerParams p;
  const cv::Rect2d b = body_from_face(cv::Rect2d(100, 50, 40, 40), p.body());
  EXPECT_DOUBLE_EQ(b.width, 110.0);   // 2.75 face widths
  EXPECT_DOUBLE_EQ(b.height, 280.0);  // 7 face heights
  EXPECT_DOUBLE_EQ(b.x, 120.0 - 55.0);
  EXPECT_DOUBLE_EQ(b.y, 50.0 - 10.0);  // 0.25 face heights above the face
}

TEST(FaceDetector, FindsMessisFaceNotHisShirt) {
  // GIVEN messi5.jpg: face (checked by eye) about x 226..265, y 93..132; the shirt and crowd next to it.
  FaceDetector d{TrackerParams{}, load_face_cascade(TrackerParams{})};
  const auto r = d.detect(photo("messi5.jpg"));
  ASSERT_TRUE(r.has_value());
  // THEN the face box is on the face
  EXPECT_TRUE(contains(r->face, {245, 112})) << r->face;
  EXPECT_LT(r->face.width, 60);
  // and the body box holds the torso (the "unicef" print at about (230, 150)), the hips (270, 235)
  // and the face, and stays inside the frame.
  EXPECT_TRUE(contains(r->body, {230, 150})) << r->body;
  EXPECT_TRUE(contains(r->body, {270, 235})) << r->body;
  EXPECT_TRUE((r->body & r->face) == r->face);
  EXPECT_LE(r->body.br().y, 342.0);
}

TEST(FaceDetector, FindsTheAstronautAndHerUpperBody) {
  // GIVEN astronaut.png: face about x 180..270, y 70..160; orange suit below down to the image bottom.
  FaceDetector d{TrackerParams{}, load_face_cascade(TrackerParams{})};
  const auto r = d.detect(photo("astronaut.png"));
  ASSERT_TRUE(r.has_value());
  EXPECT_TRUE(contains(r->face, {225, 115})) << r->face;
  EXPECT_GT(r->face.width, 70);
  // The suit: chest (230, 300), mission patch (215, 385), shoulders (120, 260) and (330, 260).
  for (cv::Point2d p : {cv::Point2d(230, 300), cv::Point2d(215, 385), cv::Point2d(120, 260), cv::Point2d(330, 260)})
    EXPECT_TRUE(contains(r->body, p)) << p << " not in " << r->body;
  EXPECT_LE(r->body.br().y, 512.0);
}

// The whole-frame search spread over frames: each step searches at most face.scan_slice_pixels (one tile at
// least), large faces first; a complete scan finds the face detect() finds, and then starts over.
TEST(FaceDetector, ScanStepsFindTheFaceWithinTheBudget) {
  TrackerParams p;
  p.face.scan_slice_pixels = 30000;
  const cv::Mat img = photo("messi5.jpg");
  FaceDetector whole(p, load_face_cascade(p)), scan(p, load_face_cascade(p));
  const auto ref = whole.detect(img);
  ASSERT_TRUE(ref.has_value());
  const int tiles = scan.scan_tiles(img.size());
  EXPECT_GT(tiles, 3);
  std::optional<FaceDetection> found;
  int steps = 0;
  while (!found && steps < tiles) {
    found = scan.scan_step(img);
    ++steps;
    EXPECT_LE(scan.last_step_pixels(), p.face.scan_slice_pixels) << "step " << steps;
    EXPECT_GT(scan.last_step_pixels(), 0.0);
  }
  ASSERT_TRUE(found.has_value()) << "not found in one scan of " << tiles << " tiles";
  EXPECT_GT(steps, 1) << "a small face should not be found in the first (coarse) step";
  // The same face as the search over the whole frame at once (the cascade's boxes differ by a tile's cut).
  const double inter = (found->face & ref->face).area();
  EXPECT_GT(inter / (found->face.area() + ref->face.area() - inter), 0.7) << found->face << " vs " << ref->face;
  // scan_slice_pixels 0: the whole frame in one step.
  p.face.scan_slice_pixels = 0;
  FaceDetector at_once(p, load_face_cascade(p));
  const auto one = at_once.scan_step(img);
  ASSERT_TRUE(one.has_value());
  EXPECT_EQ(one->face, ref->face);
}

// The LOST search around the last box within the same budget: a window whose search (with its enlarged copy,
// face.upscale) is over scan_slice_pixels is scanned over calls, each within the budget, and finds the face
// detect_all finds in it; a window within the budget is detect_all, in one call.
TEST(FaceDetector, WindowStepsStayWithinTheBudget) {
  TrackerParams p;  // face.upscale 2, scan_slice_pixels 60000
  const cv::Mat img = photo("messi5.jpg");
  const cv::Rect roi(150, 40, 200, 200);  // 40000 px, enlarged 160000: 200000 px searched at once
  FaceDetector whole(p, load_face_cascade(p)), steps(p, load_face_cascade(p));
  const auto ref = whole.detect(img, roi);
  ASSERT_TRUE(ref.has_value());
  std::vector<FaceDetection> found;
  int calls = 0;
  for (; found.empty() && calls < 20; ++calls) {
    found = steps.window_step_all(img, roi);
    EXPECT_LE(steps.last_step_pixels(), p.face.scan_slice_pixels) << "call " << calls;
    EXPECT_GT(steps.last_step_pixels(), 0.0);
  }
  ASSERT_FALSE(found.empty()) << "not found in 20 calls";
  const double inter = (found.front().face & ref->face).area();
  EXPECT_GT(inter / (found.front().face.area() + ref->face.area() - inter), 0.7) << found.front().face << " vs " << ref->face;
  // Within the budget (90x90: 8100 + 32400 px): exactly detect_all's faces, in one call.
  const cv::Rect small(200, 70, 90, 90);
  const auto in_one = steps.window_step_all(img, small);
  const auto at_once = whole.detect_all(img, small);
  ASSERT_EQ(in_one.size(), at_once.size());
  ASSERT_FALSE(in_one.empty());
  EXPECT_EQ(in_one.front().face, at_once.front().face);
  EXPECT_DOUBLE_EQ(steps.last_step_pixels(), 90.0 * 90.0 * 5);
}

// The LOST search around the last box takes no face larger than the user's last one grown by the scale gate
// (max_face): Messi's 40 px face is found up to 40 px and not below; a bound under the cascade's 20 px window
// leaves the window's search at its size out (only the enlarged copy is searched), and a window scanned over
// calls passes over the octaves whose smallest face is larger.
TEST(FaceDetector, AWindowSearchBoundedAboveTakesNoLargerFace) {
  TrackerParams p;
  const cv::Mat img = photo("messi5.jpg");
  const cv::Rect small(200, 70, 90, 90);
  FaceDetector d(p, load_face_cascade(p));
  const auto any = d.window_step_all(img, small);
  ASSERT_FALSE(any.empty());
  const double w = any.front().face.width;
  EXPECT_GT(w, 35.0);
  EXPECT_FALSE(d.window_step_all(img, small, 1.1 * w).empty());
  EXPECT_TRUE(d.window_step_all(img, small, 0.75 * w).empty());
  EXPECT_DOUBLE_EQ(d.last_step_pixels(), 90.0 * 90.0 * 5);  // 30 px: the window as it is, and enlarged
  EXPECT_TRUE(d.window_step_all(img, small, 15.0).empty());
  EXPECT_DOUBLE_EQ(d.last_step_pixels(), 90.0 * 90.0 * 4);  // 15 px: only the enlarged copy
  // Over the budget: scanned over calls; a bound below the face finds nothing in a whole cycle of the scan.
  const cv::Rect roi(150, 40, 200, 200);
  FaceDetector bounded(p, load_face_cascade(p)), open(p, load_face_cascade(p));
  bool found_bounded = false, found_open = false;
  for (int calls = 0; calls < 20; ++calls) {
    found_bounded = found_bounded || !bounded.window_step_all(img, roi, 0.75 * w).empty();
    EXPECT_LE(bounded.last_step_pixels(), p.face.scan_slice_pixels);
    found_open = found_open || !open.window_step_all(img, roi, 1.1 * w).empty();
  }
  EXPECT_FALSE(found_bounded);
  EXPECT_TRUE(found_open);
}

// A face below min_face_px is found only in the enlarged copy (face.upscale 2); a caller that takes no face
// below min_face (the re-check: half the face it expects) has the enlarged copy searched from there only, or
// not at all when every face it holds is smaller.
TEST(FaceDetector, EnlargedSearchLooksOnlyForTheFacesTheCallerTakes) {
  cv::Mat small;
  cv::resize(photo("messi5.jpg"), small, cv::Size(), 0.4, 0.4, cv::INTER_AREA);  // the face about 16 px
  const cv::Rect roi(60, 10, 80, 80);
  FaceDetector d{TrackerParams{}, load_face_cascade(TrackerParams{})};
  const auto any = d.detect(small, roi);
  ASSERT_TRUE(any.has_value());
  EXPECT_LT(any->face.width, 20.0) << any->face;
  EXPECT_TRUE(any->face.contains({98, 45})) << any->face;
  const auto from_12 = d.detect(small, roi, 12.0);
  ASSERT_TRUE(from_12.has_value());
  // The same face (the cascade groups its windows of the sizes searched: the box may differ by a window step).
  const double inter = (from_12->face & any->face).area();
  EXPECT_GT(inter / (from_12->face.area() + any->face.area() - inter), 0.7) << from_12->face << " vs " << any->face;
  EXPECT_FALSE(d.detect(small, roi, 1.5 * any->face.width).has_value());
  EXPECT_FALSE(d.detect(small, roi, 30.0).has_value());  // above the enlarged copy's largest face (25 px)
}

// The re-check's search: messi5's 16 px face (below recheck_small_face_px) is found in the window enlarged, at
// its size; an expected size that means nothing (0, negative) or a window off the frame is no crash and no
// enlarged search (the plain one, or none).
TEST(FaceDetector, ReCheckFindsASmallFaceAndTakesNonsenseSizes) {
  cv::Mat small;
  cv::resize(photo("messi5.jpg"), small, cv::Size(), 0.4, 0.4, cv::INTER_AREA);
  const cv::Rect roi(60, 10, 80, 80);
  FaceDetector d{TrackerParams{}, load_face_cascade(TrackerParams{})};
  const auto any = d.detect(small, roi);
  ASSERT_TRUE(any.has_value());
  const auto face = d.recheck(small, roi, any->face.width, 0.7);
  ASSERT_TRUE(face.has_value());
  EXPECT_TRUE(face->face.contains({98, 45})) << face->face;
  EXPECT_NEAR(face->face.width / any->face.width, 1.0, 0.15) << face->face << " vs " << any->face;
  // The plain search, from its smallest face (at the search's pyramid step, the same face as detect's).
  TrackerParams same_step;
  same_step.face.recheck_scale_factor = same_step.face.scale_factor;
  FaceDetector plain{same_step, load_face_cascade(same_step)};
  for (const double nonsense : {0.0, -5.0}) {
    const auto f = plain.recheck(small, roi, nonsense, 0.7);
    ASSERT_TRUE(f.has_value()) << nonsense;
    EXPECT_EQ(f->face, any->face) << nonsense;
  }
  EXPECT_FALSE(d.recheck(small, cv::Rect(5000, 5000, 40, 40), 10.0, 0.7).has_value());
}

TEST(FaceDetector, FindsNoFaceOutsideTheSkier) {
  // GIVEN COCO 000000000785.jpg, one skier whose person box is [280.79, 44.73, 218.7, 346.68] (COCO val2017
  // annotations, CC BY 4.0). Her face is small and partly covered: the cascade may miss it, but anything it
  // reports must be on her.
  FaceDetector d{TrackerParams{}, load_face_cascade(TrackerParams{})};
  const auto r = d.detect(photo("000000000785.jpg"));
  if (r) {
    const cv::Rect2d person(280.79, 44.73, 218.7, 346.68);
    EXPECT_TRUE((r->face & person) == r->face) << r->face;
  }
}

TEST(FaceDetector, DownscaledSearchFindsTheSameFace) {
  TrackerParams p;
  p.face.downscale = 2.0;
  p.face.min_face_px = 16;
  FaceDetector d(p, load_face_cascade(p));
  const auto r = d.detect(photo("astronaut.png"));
  ASSERT_TRUE(r.has_value());
  EXPECT_TRUE(contains(r->face, {225, 115})) << r->face;
}

TEST(FaceDetector, MissingCascadeIsAClearError) {
  TrackerParams p;
  p.face.cascade = "/nonexistent/cascade.xml";
  EXPECT_THROW(load_face_cascade(p), std::runtime_error);
}

TEST(FaceDetector, EmptyFrameFindsNothing) {
  FaceDetector d{TrackerParams{}, load_face_cascade(TrackerParams{})};
  EXPECT_FALSE(d.detect(cv::Mat()).has_value());
}

}  // namespace
}  // namespace gpilot
