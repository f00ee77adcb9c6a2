// The pose core with BlazePose's nets: loading refuses bad files by name; on real photos (data/real_people,
// hand-drawn COCO keypoints) and on the synthetic world the estimator, seeded with the person's box, finds the
// arms; the second frame is tracked without the detector; the same frames give the same landmarks bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "capture/synthetic_world.hpp"
#include "coco_keypoints.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "paths.hpp"
#include "pose/depthwise_conv.hpp"
#include "pose/pose_estimator.hpp"
#include "pose_test_models.hpp"

namespace gpilot {
namespace {

using namespace pose_landmark;

std::string temp_path(const char* name) { return ::testing::TempDir() + name; }

TEST(PoseModels, MissingFileIsRefusedNamingIt) {
  const std::string missing = temp_path("no_such_pose_detection.onnx");
  try {
    PoseModels::load(missing, pose_landmark_path(PoseParams{}));
    FAIL() << "a missing detector loaded";
  } catch (const PoseModelError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("deploy/setup"), std::string::npos) << e.what();
  }
}

TEST(PoseModels, TruncatedAndWrongShapedFilesAreRefusedNamingThem) {
  if (!pose_test::models_present()) return;
  const PoseParams p;
  // GIVEN the landmark model cut to its first 100 kB
  const std::string cut = temp_path("truncated_pose_landmark.onnx");
  {
    std::ifstream in(pose_landmark_path(p), std::ios::binary);
    std::vector<char> head(100000);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    std::ofstream(cut, std::ios::binary).write(head.data(), in.gcount());
  }
  try {
    PoseModels::load(pose_detector_path(p), cut);
    FAIL() << "a truncated landmark model loaded";
  } catch (const PoseModelError& e) {
    EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
  }
  std::remove(cut.c_str());
  // GIVEN the landmark model where the detector belongs: it does not give 2254 boxes on a 224 input
  try {
    PoseModels::load(pose_landmark_path(p), pose_landmark_path(p));
    FAIL() << "a landmark model loaded as the detector";
  } catch (const PoseModelError& e) {
    EXPECT_NE(std::string(e.what()).find(pose_landmark_path(p)), std::string::npos) << e.what();
  }
}

// The arm points of BlazePose against COCO's names.
struct ArmPoint {
  const char* coco;
  int blaze;
};
constexpr ArmPoint kArmPoints[] = {{"left_shoulder", kLeftShoulder}, {"right_shoulder", kRightShoulder},
                                   {"left_elbow", kLeftElbow},       {"right_elbow", kRightElbow},
                                   {"left_wrist", kLeftWrist},       {"right_wrist", kRightWrist}};

// Errors of the visible arm points of every annotated person, as fractions of the person's box height.
std::vector<double> arm_errors(const std::string& annotations, const std::string& images, int frames = 1) {
  const CocoKeypointFile coco = CocoKeypointFile::load(annotations);
  const PoseParams params;
  std::vector<double> errors;
  for (const CocoAnnotation& a : coco.annotations()) {
    const cv::Mat bgr = cv::imread(images + "/" + coco.image(a.image_id).file_name, cv::IMREAD_COLOR);
    if (bgr.empty()) {
      ADD_FAILURE() << "cannot read " << coco.image(a.image_id).file_name;
      continue;
    }
    PoseEstimator pose(params, PoseModels::load(params));
    PoseResult r;
    for (int f = 0; f < frames; ++f) r = pose.estimate(bgr, a.bbox, f * 33333);
    for (const ArmPoint& k : kArmPoints) {
      const auto truth = coco.keypoint(a, k.coco);
      if (!truth || truth->v != 2) continue;
      if (!r.found) {
        errors.push_back(1e9);  // a person not found misses every point
        continue;
      }
      const PoseLandmark& l = r.landmarks[static_cast<size_t>(k.blaze)];
      errors.push_back(cv::norm(cv::Point2f(l.x, l.y) - truth->p) / a.bbox.height);
    }
  }
  return errors;
}

double share_within(const std::vector<double>& errors, double bound) {
  return static_cast<double>(std::count_if(errors.begin(), errors.end(), [&](double e) { return e <= bound; })) /
         static_cast<double>(errors.size());
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct ArmAccuracy {
  size_t points = 0;
  double median = 0, within_tenth = 0, within_fifth = 0;
};

ArmAccuracy arm_accuracy(const std::string& dir, const char* name) {
  const std::vector<double> e = arm_errors(dir + "/annotations.json", dir + "/images");
  ArmAccuracy a{e.size(), median(e), share_within(e, 0.1), share_within(e, 0.2)};
  std::printf("%s: %zu visible shoulders/elbows/wrists, median error %.3f of the box height, %.1f %% within 0.1, "
              "%.1f %% within 0.2\n", name, a.points, a.median, 100 * a.within_tenth, 100 * a.within_fifth);
  return a;
}

// The shipped photos: 17 people in 12 COCO images, crowded and cut off by the frame (two people sharing one
// box, a person cut at the knees whose ROI reaches far out of the frame). Measured with lite: 102 points,
// median 0.031, 90.2 % within 0.1, 98.0 % within 0.2 (before the box ROI and the centre-line choice: median
// 0.049, 66.7 %, 74.5 %). The misses left: the two overlapping people of 000000000165, whose detections' ROIs
// each hold both.
TEST(PoseEstimatorRealPeople, ArmPointsNearTheHandDrawnKeypointsShippedPhotos) {
  if (!pose_test::models_present()) return;
  const ArmAccuracy a = arm_accuracy(resolve_project_path("data/real_people"), "data/real_people");
  ASSERT_GT(a.points, 90u);
  EXPECT_LE(a.median, 0.04);
  EXPECT_GE(a.within_tenth, 0.85);
  EXPECT_GE(a.within_fifth, 0.93);
}

// The development set (../shared/data/real_people, 62 people; not shipped). Measured with lite: 372 points,
// median 0.031, 87.4 % within 0.1, 94.9 % within 0.2 (before: 0.035, 73.7 %, 80.9 %).
TEST(PoseEstimatorRealPeople, ArmPointsNearTheHandDrawnKeypointsDevelopmentSet) {
  if (!pose_test::models_present()) return;
  const std::string dir = std::string(GPILOT_SHARED_DIR) + "/data/real_people";
  if (!std::ifstream(dir + "/annotations.json")) GTEST_SKIP() << dir << " is absent (the development set is not shipped)";
  const ArmAccuracy a = arm_accuracy(dir, "development set");
  ASSERT_GT(a.points, 300u);
  EXPECT_LE(a.median, 0.04);
  EXPECT_GE(a.within_tenth, 0.83);
  EXPECT_GE(a.within_fifth, 0.90);
}

// A small person in a crowd (000000000542, annotation 214443, 48 x 165 px) the detector does not find in the
// box: without the box ROI no pose; with it the arms within a tenth of the box height.
TEST(PoseEstimatorRealPeople, BoxRoiFindsAPersonTheDetectorMisses) {
  if (!pose_test::models_present()) return;
  const std::string dir = resolve_project_path("data/real_people");
  const CocoKeypointFile coco = CocoKeypointFile::load(dir + "/annotations.json");
  const CocoAnnotation* person = nullptr;
  for (const CocoAnnotation& a : coco.annotations())
    if (a.id == 214443) person = &a;
  ASSERT_NE(person, nullptr);
  const cv::Mat bgr = cv::imread(dir + "/images/" + coco.image(person->image_id).file_name, cv::IMREAD_COLOR);
  ASSERT_FALSE(bgr.empty());
  PoseParams without;
  without.box_roi_scale = 0;
  PoseEstimator blind(without, PoseModels::load(without));
  EXPECT_FALSE(blind.estimate(bgr, person->bbox, 0).found);
  const PoseParams params;
  PoseEstimator pose(params, PoseModels::load(params));
  const PoseResult r = pose.estimate(bgr, person->bbox, 0);
  ASSERT_TRUE(r.found);
  EXPECT_FLOAT_EQ(r.roi.size, person->bbox.height * static_cast<float>(params.box_roi_scale));
  int checked = 0;
  for (const ArmPoint& k : kArmPoints) {
    const auto truth = coco.keypoint(*person, k.coco);
    if (!truth || truth->v != 2) continue;
    const PoseLandmark& l = r.landmarks[static_cast<size_t>(k.blaze)];
    EXPECT_LT(cv::norm(cv::Point2f(l.x, l.y) - truth->p) / person->bbox.height, 0.1) << k.coco;
    ++checked;
  }
  EXPECT_EQ(checked, 6);
}

// The synthetic tour's key poses at 3 m, seeded with the true user box: the figure's wrists and elbows where
// the world drew them (the person's own left is BlazePose's left).
const SyntheticWorld& tour_world() {
  static const SyntheticWorld world(SyntheticParams{}, Scenario::load("tour"), 7);
  return world;
}

double tour_time_of(int gesture) {
  if (const auto t = tour_world().scenario().key_time_of(gesture)) return *t;
  ADD_FAILURE() << "tour has no gesture " << gesture;
  return 0.0;
}

TEST(PoseEstimatorSynthetic, FindsTheFiguresArmsInEveryKeyPose) {
  if (!pose_test::models_present()) return;
  const PoseParams params;
  for (int gesture : {ground_truth_t::GESTURE_REST, ground_truth_t::GESTURE_OUT, ground_truth_t::GESTURE_CLOSER,
                      ground_truth_t::GESTURE_DOWN}) {
    SCOPED_TRACE(gesture);
    const SyntheticFrame f = tour_world().render(tour_time_of(gesture), 0, std::nullopt);
    PoseEstimator pose(params, PoseModels::load(params));
    const PoseResult r = pose.estimate(f.bgr, f.truth.user_box, 0);
    ASSERT_TRUE(r.found);
    EXPECT_TRUE(r.detector_ran);
    const float h = f.truth.user_box.height;
    auto at = [&](int i) { return cv::Point2f(r.landmarks[static_cast<size_t>(i)].x, r.landmarks[static_cast<size_t>(i)].y); };
    // within a tenth of the user box height (measured with lite: at most 0.046, REST/OUT/CLOSER/DOWN)
    EXPECT_LT(cv::norm(at(kLeftWrist) - f.truth.left_wrist) / h, 0.1);
    EXPECT_LT(cv::norm(at(kRightWrist) - f.truth.right_wrist) / h, 0.1);
    EXPECT_LT(cv::norm(at(kLeftElbow) - f.truth.left_elbow) / h, 0.1);
    EXPECT_LT(cv::norm(at(kRightElbow) - f.truth.right_elbow) / h, 0.1);
    std::printf("gesture %d: wrists %.3f %.3f elbows %.3f %.3f of box height\n", gesture,
                cv::norm(at(kLeftWrist) - f.truth.left_wrist) / h, cv::norm(at(kRightWrist) - f.truth.right_wrist) / h,
                cv::norm(at(kLeftElbow) - f.truth.left_elbow) / h, cv::norm(at(kRightElbow) - f.truth.right_elbow) / h);
  }
}

// Frames of the tour, 25 fps, from the REST key pose on.
std::vector<SyntheticFrame> tour_frames(int n) {
  std::vector<SyntheticFrame> frames;
  const double t0 = tour_time_of(ground_truth_t::GESTURE_OUT) - 0.5;
  for (int i = 0; i < n; ++i) frames.push_back(tour_world().render(t0 + i * 0.04, i, std::nullopt));
  return frames;
}

TEST(PoseEstimatorSynthetic, TracksWithoutTheDetectorAfterTheFirstFrame) {
  if (!pose_test::models_present()) return;
  const PoseParams params;
  PoseEstimator pose(params, PoseModels::load(params));
  const std::vector<SyntheticFrame> frames = tour_frames(6);
  for (size_t i = 0; i < frames.size(); ++i) {
    const PoseResult r = pose.estimate(frames[i].bgr, frames[i].truth.user_box, static_cast<int64_t>(i) * 40000);
    ASSERT_TRUE(r.found) << "frame " << i;
    EXPECT_EQ(r.detector_ran, i == 0) << "frame " << i;
  }
  EXPECT_EQ(pose.counters().detector_runs, 1);
  EXPECT_EQ(pose.counters().frames_tracked, 5);
  // a user box far from the tracked hips hands over to the detector (which finds no one there)
  const PoseResult moved = pose.estimate(frames[0].bgr, cv::Rect2f(5, 5, 40, 100), 6 * 40000);
  EXPECT_TRUE(moved.detector_ran);
  EXPECT_FALSE(moved.found);
  // reset: the detector again
  pose.reset();
  EXPECT_TRUE(pose.estimate(frames[1].bgr, frames[1].truth.user_box, 7 * 40000).detector_ran);
}

// data/pose/dark_skin_arm_up.jpg (the dark-skin e2e, the drone high, the body at the frame's bottom edge): the
// ROI the pose's auxiliary points give lies 16 px below the detector's and scores 0.4, the detector's 0.9. With
// reseed_in_frame the frame whose tracked ROI fails is seeded at once and the track keeps to the seed's ROI, one
// landmark run a frame; without, that frame has no pose (and in the e2e run every other frame had none: an arm
// held up was no command for 3 s). Ten frames of the one image, utimes 40 ms apart.
TEST(PoseEstimatorSynthetic, ATrackedFrameWithoutAPoseIsSeededAtOnceAndTheTrackKeepsTheSeedsRoi) {
  if (!pose_test::models_present()) return;
  const cv::Mat bgr = cv::imread(resolve_project_path("data/pose/dark_skin_arm_up.jpg"), cv::IMREAD_COLOR);
  ASSERT_FALSE(bgr.empty());
  const cv::Rect2f user_box(261.2f, 250.9f, 76.65f, 195.1f);  // USER_TRACK's box of that frame
  const auto run = [&](bool reseed) {
    PoseParams params;
    params.reseed_in_frame = reseed;
    PoseEstimator pose(params, PoseModels::load(params));
    int found = 0;
    for (int i = 0; i < 10; ++i) found += pose.estimate(bgr, user_box, i * 40000).found ? 1 : 0;
    return std::make_pair(found, pose.counters());
  };
  const auto [found_reseeding, reseeding] = run(true);
  EXPECT_EQ(found_reseeding, 10);
  EXPECT_EQ(reseeding.reseeds, 1);  // once: then the corrected ROIs find the pose
  EXPECT_EQ(reseeding.reseeds_found, 1);
  EXPECT_EQ(reseeding.detector_runs, 2);
  const auto [found_plain, plain] = run(false);
  EXPECT_LE(found_plain, 9) << "the frame no longer makes the auxiliary points' ROI fail: the test shows nothing";
  EXPECT_EQ(plain.reseeds, 0);
}

TEST(PoseEstimatorSynthetic, SameFramesGiveTheSameLandmarksBitForBit) {
  if (!pose_test::models_present()) return;
  const PoseParams params;
  PoseEstimator a(params, PoseModels::load(params)), b(params, PoseModels::load(params));
  const std::vector<SyntheticFrame> frames = tour_frames(5);
  for (size_t i = 0; i < frames.size(); ++i) {
    const int64_t t = static_cast<int64_t>(i) * 40000;
    const PoseResult ra = a.estimate(frames[i].bgr, frames[i].truth.user_box, t);
    const PoseResult rb = b.estimate(frames[i].bgr, frames[i].truth.user_box, t);
    ASSERT_TRUE(ra.found);
    EXPECT_EQ(std::memcmp(ra.landmarks.data(), rb.landmarks.data(), sizeof(PoseLandmarks)), 0) << "frame " << i;
    EXPECT_EQ(ra.pose_flag, rb.pose_flag);
  }
}

// The nets with our depthwise convolution (the default) hold it in place of OpenCV's 5x5 ones and give OpenCV's
// landmarks over tracked frames (the ROIs follow the landmarks, so a difference would grow). Not bit for bit:
// the sums run in another order, and through the nets' 30-odd layers that moves a landmark by about 0.1 px and a
// visibility or the pose flag by about 1e-3 (measured: 0.107 px, 8.8e-4), as OpenCV's own SIMD paths do between
// CPUs.
TEST(PoseEstimatorSynthetic, FastDepthwiseGivesOpenCVsLandmarks) {
  if (!pose_test::models_present()) return;
  PoseParams opencv;
  opencv.fast_depthwise = false;
  PoseModels fast_models = PoseModels::load(PoseParams{});
  for (cv::dnn::Net* net : {&fast_models.detector.net, &fast_models.landmark.net}) {
    int ours = 0;
    for (const std::string& name : net->getLayerNames()) ours += net->getLayer(name)->type == kDepthwiseConvLayerType;
    EXPECT_GE(ours, 8) << "the depthwise 5x5 convolutions are not ours";
  }
  PoseEstimator fast(PoseParams{}, std::move(fast_models)), own(opencv, PoseModels::load(opencv));
  const std::vector<SyntheticFrame> frames = tour_frames(5);
  double worst_px = 0, worst_score = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const int64_t t = static_cast<int64_t>(i) * 40000;
    const PoseResult a = fast.estimate(frames[i].bgr, frames[i].truth.user_box, t);
    const PoseResult b = own.estimate(frames[i].bgr, frames[i].truth.user_box, t);
    ASSERT_TRUE(a.found && b.found) << "frame " << i;
    worst_score = std::max(worst_score, static_cast<double>(std::abs(a.pose_flag - b.pose_flag)));
    for (size_t k = 0; k < a.landmarks.size(); ++k) {
      const PoseLandmark &p = a.landmarks[k], &q = b.landmarks[k];
      worst_px = std::max(worst_px, static_cast<double>(std::hypot(p.x - q.x, p.y - q.y)));
      worst_score = std::max(worst_score, static_cast<double>(std::abs(p.visibility - q.visibility)));
    }
  }
  std::printf("fast depthwise: landmarks at most %.4f px, visibility and pose flag %.5f from OpenCV's\n", worst_px, worst_score);
  EXPECT_LT(worst_px, 0.5);
  EXPECT_LT(worst_score, 0.005);
}

TEST(PoseEstimator, EmptyOrWrongTypeFrameIsAnInvalidArgument) {
  if (!pose_test::models_present()) return;
  const PoseParams params;
  PoseEstimator pose(params, PoseModels::load(params));
  EXPECT_THROW(pose.estimate(cv::Mat(), {}, 0), std::invalid_argument);
  EXPECT_THROW(pose.estimate(cv::Mat(48, 64, CV_8UC1, cv::Scalar(0)), {}, 0), std::invalid_argument);
  EXPECT_THROW(pose.estimate(cv::Mat(48, 64, CV_8UC3, cv::Scalar(0)), cv::Rect2f(0, 0, NAN, 1), 0), std::invalid_argument);
  // a black frame: no one, no NaN
  const PoseResult r = pose.estimate(cv::Mat(480, 640, CV_8UC3, cv::Scalar(0, 0, 0)), {}, 0);
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.counters.nonfinite_outputs, 0);
}

}  // namespace
}  // namespace gpilot
