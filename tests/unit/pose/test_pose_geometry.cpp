// The pose core's arithmetic without the nets: the detector's anchors and decoding, weighted NMS, the rotated
// ROI (from a detection and from auxiliary points, rotation sign included), the crop and its inverse, the
// choice of the user's detection, PoseParams' rules.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "config.hpp"
#include "pose/landmark_model.hpp"
#include "pose/person_detector.hpp"
#include "pose/pose_estimator.hpp"
#include "pose/pose_params.hpp"
#include "pose/pose_roi.hpp"
#include "pose/ssd_anchors.hpp"
#include "pose/weighted_nms.hpp"

namespace gpilot {
namespace {

TEST(SsdAnchors, CountAndKnownAnchorsOfEachFeatureMap) {
  // GIVEN pose_detection_cpu.pbtxt's options WHEN the anchors are made
  const std::vector<SsdAnchor>& a = pose_detector_anchors();
  // THEN 28x28x2 + 14x14x2 + 7x7x6 = 2254, the count the net outputs
  ASSERT_EQ(a.size(), 2254u);
  // stride 8: two anchors per cell, row-major
  EXPECT_FLOAT_EQ(a[0].x_center, 0.5f / 28);
  EXPECT_FLOAT_EQ(a[0].y_center, 0.5f / 28);
  EXPECT_FLOAT_EQ(a[1].x_center, 0.5f / 28);
  EXPECT_FLOAT_EQ(a[2].x_center, 1.5f / 28);
  EXPECT_FLOAT_EQ(a[56].y_center, 1.5f / 28);  // second row
  // stride 16 starts at 1568
  EXPECT_FLOAT_EQ(a[1567].x_center, 27.5f / 28);
  EXPECT_FLOAT_EQ(a[1568].x_center, 0.5f / 14);
  // the three stride-32 layers share one 7x7 map, six anchors a cell, from 1960
  EXPECT_FLOAT_EQ(a[1960].x_center, 0.5f / 7);
  EXPECT_FLOAT_EQ(a[1965].x_center, 0.5f / 7);
  EXPECT_FLOAT_EQ(a[1966].x_center, 1.5f / 7);
  EXPECT_FLOAT_EQ(a[2253].x_center, 6.5f / 7);
  EXPECT_FLOAT_EQ(a[2253].y_center, 6.5f / 7);
  EXPECT_FLOAT_EQ(a[2253].width, 1.0f);
}

TEST(DecodePersonDetections, OffsetsFromTheAnchorSigmoidScoresClippedAndNonFiniteRowsCounted) {
  // GIVEN raw outputs where only anchors 0, 1 and 2 say something
  std::vector<float> boxes(2254 * 12, 0.0f), scores(2254, -1000.0f);
  const float row0[12] = {10, -4, 50, 60, 3, 5, 3, -45, 3, -20, 3, -30};
  std::copy(row0, row0 + 12, boxes.begin());
  scores[0] = 2.0f;
  scores[1] = std::numeric_limits<float>::quiet_NaN();
  scores[2] = 1000.0f;  // clipped at 100: score 1
  PoseParams p;
  int nonfinite = 0;
  // WHEN decoded
  const std::vector<PersonDetection> d = decode_person_detections(boxes.data(), scores.data(), p, &nonfinite);
  // THEN anchor 0 (centre 4, 4 input pixels): box centre (14, 0), 50 x 60; keypoints from the anchor centre
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NEAR(d[0].score, 0.880797f, 1e-5);
  EXPECT_NEAR(d[0].face.x, 14 - 25, 1e-4);
  EXPECT_NEAR(d[0].face.y, 0 - 30, 1e-4);
  EXPECT_NEAR(d[0].face.width, 50, 1e-4);
  EXPECT_NEAR(d[0].face.height, 60, 1e-4);
  EXPECT_NEAR(d[0].keypoints[0].x, 7, 1e-4);
  EXPECT_NEAR(d[0].keypoints[0].y, 9, 1e-4);
  EXPECT_NEAR(d[0].keypoints[1].y, -41, 1e-4);
  // anchor 2 (centre 12, 4), every regression 0: a point box at the anchor, score exactly 1 after clipping
  EXPECT_FLOAT_EQ(d[1].score, 1.0f);
  EXPECT_NEAR(d[1].face.x, 12, 1e-4);
  // the NaN row is skipped and counted; the rest score below the threshold
  EXPECT_EQ(nonfinite, 1);
}

PersonDetection det(float score, cv::Rect2f face, cv::Point2f k0) {
  PersonDetection d;
  d.score = score;
  d.face = face;
  d.keypoints = {k0, k0 + cv::Point2f(0, -10), k0, k0};
  return d;
}

TEST(WeightedNms, OverlappingDetectionsAveragedByScoreTheOthersKept) {
  // GIVEN A (0.9) and B (0.6) overlapping by IoU 0.82, C (0.7) apart
  const std::vector<PersonDetection> in = {det(0.6f, {1, 0, 10, 10}, {3, 6}), det(0.7f, {50, 50, 10, 10}, {50, 50}),
                                           det(0.9f, {0, 0, 10, 10}, {0, 0})};
  // WHEN merged at MediaPipe's threshold
  const std::vector<PersonDetection> out = weighted_nms(in, 0.3f);
  // THEN A+B weighted by 0.9 and 0.6, A's score kept, then C
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].score, 0.9f);
  EXPECT_NEAR(out[0].face.x, 0.4f, 1e-5);
  EXPECT_NEAR(out[0].face.width, 10.0f, 1e-5);
  EXPECT_NEAR(out[0].keypoints[0].x, 1.2f, 1e-5);
  EXPECT_NEAR(out[0].keypoints[0].y, 2.4f, 1e-5);
  EXPECT_FLOAT_EQ(out[1].score, 0.7f);
  EXPECT_FLOAT_EQ(out[1].face.x, 50.0f);
}

TEST(WeightedNms, OverlapAtTheThresholdIsNotMerged) {
  // GIVEN two boxes of IoU exactly 1/3 (10x10 overlapping by half: 50 / 150)
  const std::vector<PersonDetection> in = {det(0.9f, {0, 0, 10, 10}, {0, 0}), det(0.8f, {5, 0, 10, 10}, {5, 0})};
  EXPECT_FLOAT_EQ(face_iou(in[0], in[1]), 50.0f / 150.0f);
  // THEN merged above it, kept apart at it
  EXPECT_EQ(weighted_nms(in, 0.3f).size(), 1u);
  EXPECT_EQ(weighted_nms(in, 50.0f / 150.0f).size(), 2u);
}

TEST(PoseRoi, UprightPersonHasNoRotationAndTheMediaPipeSize) {
  // GIVEN the hips at (100, 200) and the scale point 100 px straight above
  const PoseRoi r = roi_from_alignment({100, 200}, {100, 100}, 1.25f);
  // THEN centred on the hips, side 2 x 100 x 1.25, no rotation
  EXPECT_FLOAT_EQ(r.centre.x, 100);
  EXPECT_FLOAT_EQ(r.centre.y, 200);
  EXPECT_FLOAT_EQ(r.size, 250);
  EXPECT_NEAR(r.rotation, 0.0f, 1e-6);
  // and the crop's top centre is 125 px above the hips, its corners the square's
  const cv::Matx23d m = crop_to_image(r, 256);
  const cv::Point2f top = apply_affine(m, {128, 0});
  EXPECT_NEAR(top.x, 100, 1e-4);
  EXPECT_NEAR(top.y, 75, 1e-4);
  const cv::Point2f corner = apply_affine(m, {256, 256});
  EXPECT_NEAR(corner.x, 225, 1e-4);
  EXPECT_NEAR(corner.y, 325, 1e-4);
}

TEST(PoseRoi, RotationSignHeadToTheRightTurnsTheCropsUpToTheRight) {
  // GIVEN a person lying with the head to the image's right (scale point right of the hips)
  const PoseRoi right = roi_from_alignment({100, 200}, {200, 200}, 1.25f);
  // THEN rotation +90 deg and the crop's top centre lies right of the hips (the head is up in the crop)
  EXPECT_NEAR(right.rotation, CV_PI / 2, 1e-6);
  const cv::Point2f top = apply_affine(crop_to_image(right, 256), {128, 0});
  EXPECT_NEAR(top.x, 225, 1e-3);
  EXPECT_NEAR(top.y, 200, 1e-3);
  // head to the left: -90 deg; upside down: +-180 deg (normalised into [-pi, pi))
  EXPECT_NEAR(roi_from_alignment({100, 200}, {0, 200}, 1.25f).rotation, -CV_PI / 2, 1e-6);
  EXPECT_NEAR(std::fabs(roi_from_alignment({100, 200}, {100, 300}, 1.25f).rotation), CV_PI, 1e-6);
  // leaning: the scale point up and to the right by 45 deg: +45 deg
  EXPECT_NEAR(roi_from_alignment({0, 0}, {10, -10}, 1.0f).rotation, CV_PI / 4, 1e-6);
}

TEST(PoseRoi, NormalizeRadiansWrapsIntoMinusPiToPi) {
  // A turn and a rotation summed (the track's corrected ROI) can leave [-pi, pi): wrapped back, same direction.
  EXPECT_NEAR(normalize_radians(0.5f), 0.5f, 1e-6);
  EXPECT_NEAR(normalize_radians(static_cast<float>(CV_PI) + 0.25f), -CV_PI + 0.25, 1e-6);
  EXPECT_NEAR(normalize_radians(-static_cast<float>(CV_PI) - 0.25f), CV_PI - 0.25, 1e-6);
  EXPECT_NEAR(normalize_radians(static_cast<float>(5 * CV_PI + 0.5)), -CV_PI + 0.5, 1e-5);
  EXPECT_NEAR(normalize_radians(static_cast<float>(-7 * CV_PI - 0.5)), CV_PI - 0.5, 1e-5);
}

TEST(PoseRoi, AuxiliaryPointsMakeTheSameRoiAsDetectionKeypoints) {
  // GIVEN the aux points 33 (centre) and 34 (scale point) of a leaning person: the same rule as a detection
  const PoseRoi r = roi_from_alignment({320, 260}, {350, 140}, 1.25f);
  EXPECT_NEAR(r.size, 2 * std::hypot(30.0, 120.0) * 1.25, 1e-3);
  EXPECT_NEAR(r.rotation, CV_PI / 2 - std::atan2(120.0, 30.0), 1e-6);
}

TEST(PoseRoi, CropMapAndItsInverseRoundTrip) {
  const PoseRoi r{{321.5f, 240.25f}, 180.0f, 0.6f};
  const cv::Matx23d to_image = crop_to_image(r, 256), to_crop = image_to_crop(r, 256);
  for (const cv::Point2f p : {cv::Point2f(0, 0), cv::Point2f(256, 0), cv::Point2f(17.5f, 200.25f)}) {
    const cv::Point2f back = apply_affine(to_crop, apply_affine(to_image, p));
    EXPECT_NEAR(back.x, p.x, 1e-3);
    EXPECT_NEAR(back.y, p.y, 1e-3);
  }
  // the crop's centre is the ROI's centre
  const cv::Point2f c = apply_affine(to_image, {128, 128});
  EXPECT_NEAR(c.x, 321.5f, 1e-4);
  EXPECT_NEAR(c.y, 240.25f, 1e-4);
}

TEST(PoseRoi, WarpSamplesTheImageWhereTheMapSaysPixelCentresIncluded) {
  // GIVEN an image whose value is a linear function of the pixel centre (bilinear sampling is exact on it)
  cv::Mat image(480, 640, CV_32F);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) image.at<float>(y, x) = static_cast<float>((x + 0.5) + 2 * (y + 0.5));
  const PoseRoi r{{300.0f, 220.0f}, 200.0f, -0.4f};
  // WHEN the rotated ROI is warped to 64 x 64
  const cv::Mat crop = warp_roi(image, r, 64);
  // THEN each crop pixel holds the value at its centre's image point: within warpAffine's 1/32-pixel coordinate
  // steps (x + 2y: up to 3/64), where half a pixel off would be 1.5
  const cv::Matx23d m = crop_to_image(r, 64);
  for (const cv::Point p : {cv::Point(0, 0), cv::Point(63, 0), cv::Point(31, 40), cv::Point(63, 63)}) {
    const cv::Point2f q = apply_affine(m, {p.x + 0.5f, p.y + 0.5f});
    EXPECT_NEAR(crop.at<float>(p), q.x + 2 * q.y, 0.1) << p;
  }
}

TEST(ChooseUserDetection, HipsInTheBoxAndBestOverlapNeverTheBystander) {
  // GIVEN the user's box and three detections: a better-scoring bystander beside it, the user, and a small
  // person whose hips fall in the box but whose body is far smaller than the box
  const cv::Rect2f user(200, 100, 100, 300);
  PersonDetection bystander = det(0.95f, {420, 110, 30, 30}, {440, 260});
  bystander.keypoints[1] = {440, 110};
  PersonDetection me = det(0.8f, {230, 110, 30, 30}, {250, 260});
  me.keypoints[1] = {250, 110};
  PersonDetection small = det(0.9f, {240, 300, 10, 10}, {245, 340});
  small.keypoints[1] = {245, 320};
  // WHEN chosen
  const auto chosen = choose_user_detection({bystander, small, me}, user);
  // THEN the user's
  ASSERT_TRUE(chosen);
  EXPECT_FLOAT_EQ(chosen->score, 0.8f);
  // no detection in the box: none; no box: the best-scoring
  EXPECT_FALSE(choose_user_detection({bystander}, user));
  EXPECT_FLOAT_EQ(choose_user_detection({bystander, me}, cv::Rect2f())->score, 0.95f);
}

TEST(ChooseUserDetection, OfTwoPeopleInOneBoxTheOneItIsDrawnAround) {
  // GIVEN a box around one person, the hips of a neighbour also inside it near its edge; the neighbour's
  // full-body square overlaps the box more (square IoU, the former rule, picked the neighbour)
  const cv::Rect2f user(200, 100, 200, 400);
  PersonDetection me = det(0.6f, {280, 110, 40, 40}, {300, 330});
  me.keypoints[1] = {300, 130};  // body 400 px: the box height
  PersonDetection neighbour = det(0.9f, {190, 140, 40, 40}, {210, 300});
  neighbour.keypoints[1] = {205, 130};  // body 340 px
  // WHEN ranked
  const auto ranked = user_detection_candidates({neighbour, me}, user, 5);
  // THEN the one centred in the box and of its height first, the neighbour second
  ASSERT_EQ(ranked.size(), 2u);
  EXPECT_FLOAT_EQ(ranked[0].score, 0.6f);
  EXPECT_FLOAT_EQ(ranked[1].score, 0.9f);
  EXPECT_EQ(user_detection_candidates({neighbour, me}, user, 1).size(), 1u);
  EXPECT_FLOAT_EQ(choose_user_detection({neighbour, me}, user)->score, 0.6f);
  // no box: as given (best score first), at most max_count
  EXPECT_FLOAT_EQ(user_detection_candidates({neighbour, me}, cv::Rect2f(), 1).at(0).score, 0.9f);
}

TEST(BoxRoi, UprightCentredOnTheBoxSideTheLongSideTimesScale) {
  const PoseRoi r = box_roi(cv::Rect2f(100, 50, 80, 200), 1.25f);
  EXPECT_FLOAT_EQ(r.centre.x, 140.0f);
  EXPECT_FLOAT_EQ(r.centre.y, 150.0f);
  EXPECT_FLOAT_EQ(r.size, 250.0f);
  EXPECT_FLOAT_EQ(r.rotation, 0.0f);
  EXPECT_FLOAT_EQ(box_roi(cv::Rect2f(0, 0, 300, 100), 1.0f).size, 300.0f);
}

TEST(LandmarksBoxIou, BoundingBoxOfTheLandmarksAgainstTheBox) {
  // GIVEN landmarks spanning x 100..200, y 50..250 (all at the centre but two corners)
  PoseLandmarks l{};
  for (PoseLandmark& p : l) p = {150, 150, 0, 1, 1};
  l[0] = {100, 50, 0, 1, 1};
  l[32] = {200, 250, 0, 1, 1};
  // THEN the IoU with the same box is 1, with its left half 0.5, with a box beside it 0
  EXPECT_NEAR(landmarks_box_iou(l, cv::Rect2f(100, 50, 100, 200)), 1.0, 1e-9);
  EXPECT_NEAR(landmarks_box_iou(l, cv::Rect2f(100, 50, 50, 200)), 0.5, 1e-9);
  EXPECT_NEAR(landmarks_box_iou(l, cv::Rect2f(300, 50, 100, 200)), 0.0, 1e-9);
}

TEST(DecodePoseLandmarks, CropPixelsToFramePixelsZScaledLikeXVisibilitySigmoidAndNaNRefused) {
  // GIVEN a ROI of side 512 centred at (300, 200), upright: crop pixel = 2 frame pixels
  const PoseRoi roi{{300, 200}, 512, 0};
  std::vector<float> v(39 * 5, 0.0f);
  const float wrist[5] = {64, 192, -10, 0, 2};  // left wrist
  std::copy(wrist, wrist + 5, v.begin() + 15 * 5);
  v[33 * 5] = 128, v[33 * 5 + 1] = 128;  // aux centre at the crop centre
  v[34 * 5] = 128, v[34 * 5 + 1] = 28;   // aux scale point 100 crop px above
  // WHEN decoded
  const LandmarkOutput out = decode_pose_landmarks(v.data(), 0.9f, roi);
  // THEN frame pixels: (300 + 2 (64 - 128), 200 + 2 (192 - 128)); z x 2; sigmoid(0) = 0.5, sigmoid(2) = 0.8808
  ASSERT_TRUE(out.finite);
  EXPECT_FLOAT_EQ(out.pose_flag, 0.9f);
  EXPECT_NEAR(out.landmarks[15].x, 172, 1e-3);
  EXPECT_NEAR(out.landmarks[15].y, 328, 1e-3);
  EXPECT_NEAR(out.landmarks[15].z, -20, 1e-4);
  EXPECT_NEAR(out.landmarks[15].visibility, 0.5f, 1e-6);
  EXPECT_NEAR(out.landmarks[15].presence, 0.880797f, 1e-5);
  EXPECT_NEAR(out.aux[0].x, 300, 1e-3);
  EXPECT_NEAR(out.aux[1].y, 0, 1e-3);
  // a NaN anywhere among the 35 points read (or in the flag): not finite
  v[20 * 5 + 2] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(decode_pose_landmarks(v.data(), 0.9f, roi).finite);
  v[20 * 5 + 2] = 0;
  EXPECT_FALSE(decode_pose_landmarks(v.data(), std::numeric_limits<float>::infinity(), roi).finite);
}

TEST(PoseParams, DefaultsPassAndAnUnknownModelOrBadRangeIsRefusedByName) {
  EXPECT_NO_THROW(Config().section<PoseParams>("pose"));
  const PoseParams p = Config::from_string("pose: {model: full, roi_scale: 1.5, smoothing: {aux: {beta: 2}}}").section<PoseParams>("pose");
  EXPECT_EQ(p.model, "full");
  EXPECT_DOUBLE_EQ(p.roi_scale, 1.5);
  EXPECT_DOUBLE_EQ(p.smoothing.aux.beta, 2.0);
  EXPECT_DOUBLE_EQ(p.smoothing.aux.min_cutoff, 0.01);
  try {
    Config::from_string("pose: {model: heavy}").section<PoseParams>("pose");
    FAIL() << "heavy accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("pose.model"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Config::from_string("pose: {pose_flag_threshold: 1.5}").section<PoseParams>("pose"), ConfigError);
  EXPECT_THROW(Config::from_string("pose: {seed_candidates: 0}").section<PoseParams>("pose"), ConfigError);
  EXPECT_THROW(Config::from_string("pose: {box_roi_scale: -1}").section<PoseParams>("pose"), ConfigError);
  EXPECT_THROW(Config::from_string("pose: {smoothing: {landmarks: {min_cutoff: 0}}}").section<PoseParams>("pose"), ConfigError);
}

}  // namespace
}  // namespace gpilot
