// The tracker's own face search (Haar cascade from opencv-data, the tracker's defaults) finds the synthetic
// face where the ground truth says it is, in every key pose of the tour at the default distance (3 m), and
// at rest at 2 m and 4 m (whole frame); the body box it builds is the ground truth's user box.
#include <gtest/gtest.h>

#include <filesystem>

#include "scenario.hpp"
#include "synthetic_world.hpp"
#include "tracker/face_cascade.hpp"
#include "tracker/face_detector.hpp"

namespace gpilot {
namespace {

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

class SyntheticFace : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(TrackerParams{}.face.cascade))
      GTEST_SKIP() << "no Haar cascade at " << TrackerParams{}.face.cascade << " (Debian package opencv-data)";
  }
};

TEST_F(SyntheticFace, HaarFindsTheFaceInEveryPoseOfTheTour) {
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("tour"), 3);
  FaceDetector detector{TrackerParams{}, load_face_cascade(TrackerParams{})};
  for (double t : world.scenario().key_times()) {
    const SyntheticFrame f = world.render(t, 0, std::nullopt);
    SCOPED_TRACE(std::to_string(t) + " s, " + gesture_name(f.truth.gesture));
    // One search in the upper middle of the frame (the person stands there in every pose) keeps the test fast.
    const cv::Rect area(160, 60, 320, 240);
    auto d = detector.detect(f.bgr(area));
    ASSERT_TRUE(d.has_value()) << "no face found";
    d->face += cv::Point2d(area.tl());
    EXPECT_GT(iou(d->face, f.truth.face_box), 0.8) << d->face << " vs truth " << f.truth.face_box;
    EXPECT_GT(iou(body_from_face(d->face, TrackerParams{}.body()), f.truth.user_box), 0.8) << " vs truth " << f.truth.user_box;
  }
}

TEST_F(SyntheticFace, HaarFindsTheFaceFromTwoToFourMetres) {
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("idle"), 3);
  FaceDetector detector{TrackerParams{}, load_face_cascade(TrackerParams{})};
  for (double distance : {2.0, 4.0}) {
    SCOPED_TRACE(std::to_string(distance) + " m");
    const SyntheticFrame f = world.render(1.0, 0, CameraPose{3.0 - distance, 0.0, -1.5, 0.0});
    const auto d = detector.detect(f.bgr);
    ASSERT_TRUE(d.has_value()) << "no face found";
    EXPECT_GT(iou(d->face, f.truth.face_box), 0.8) << d->face << " vs truth " << f.truth.face_box;
  }
}

}  // namespace
}  // namespace gpilot
