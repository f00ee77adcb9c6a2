// Scenes that the hands stage finds hard, made honestly: the warm wall (a textured plane behind the person,
// where it should be, occluded by the person, skin-coloured to the project's UCI skin model), short and long
// sleeves, the dark skin tone (darker hands, a tinted face), and the nuisances backdrop as shot.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "gpilot/ground_truth_t.hpp"
#include "hands/hands_params.hpp"
#include "hands/skin_model.hpp"
#include "paths.hpp"
#include "synthetic_world.hpp"

namespace gpilot {
namespace {

const SkinClassifier& skin() {
  static const HandsParams hp;
  static const SkinClassifier c(SkinModel::load(resolve_project_path(hp.skin.model)), hp.skin.threshold);
  return c;
}

// The first scenario time at which a keyframe with this gesture (and, if given, this predicate) is held.
double time_of(const Scenario& s, int gesture) {
  if (const auto t = s.key_time_of(gesture)) return *t;
  ADD_FAILURE() << s.name() << " has no " << gesture_name(gesture);
  return 0.0;
}

uchar label_at(const cv::Mat& labels, const cv::Point2f& p) {
  return labels.at<uchar>(static_cast<int>(std::lround(p.y)), static_cast<int>(std::lround(p.x)));
}

double luma(const cv::Vec3b& c) { return 0.114 * c[0] + 0.587 * c[1] + 0.299 * c[2]; }

// Mean luminance of the pixels with one of the labels.
double mean_luma(const cv::Mat& bgr, const cv::Mat& labels, std::initializer_list<PartLabel> which) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x)
      for (PartLabel l : which)
        if (labels.at<uchar>(y, x) == static_cast<uchar>(l)) sum += luma(bgr.at<cv::Vec3b>(y, x)), ++n;
  EXPECT_GT(n, 50) << "too few labelled pixels";
  return n ? sum / n : 0.0;
}

TEST(Scenes, EveryShippedScenarioLoadsAndTheNewOnesSayWhatTheyAre) {
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(resolve_project_path("deploy/scenarios"))) {
    if (e.path().extension() != ".yaml") continue;
    SCOPED_TRACE(e.path().string());
    const Scenario s = Scenario::load(e.path().string());
    EXPECT_EQ(s.name(), e.path().stem().string());
    EXPECT_NO_THROW(SyntheticWorld(SyntheticParams{}, s, 1));
    ++files;
  }
  EXPECT_GE(files, 7);

  const Scenario ww = Scenario::load("warm-wall"), ds = Scenario::load("dark-skin");
  EXPECT_TRUE(ww.wall().present);
  EXPECT_DOUBLE_EQ(ww.wall().distance_m, 1.0);
  EXPECT_EQ(ww.wall().texture, "wood");
  EXPECT_FALSE(ww.person().long_sleeves);
  EXPECT_EQ(ds.person().skin_tone, "dark");
  EXPECT_TRUE(ds.person().tint_face);
  // both fly every gesture of the paper, like the tour, with OUT to both sides
  for (const Scenario* s : {&ww, &ds}) {
    for (int g = ground_truth_t::GESTURE_REST; g <= ground_truth_t::GESTURE_FURTHER; ++g) {
      bool seen = false;
      for (const auto& k : s->keyframes()) seen = seen || k.state.gesture == g;
      EXPECT_TRUE(seen) << s->name() << " " << gesture_name(g);
    }
    EXPECT_GE(s->duration_s(), 60.0);
  }
  // the tour and idle are as they were: no wall, short sleeves, the portrait as shot
  for (const char* name : {"tour", "idle"}) {
    const Scenario s = Scenario::load(name);
    EXPECT_FALSE(s.wall().present) << name;
    EXPECT_FALSE(s.person().long_sleeves) << name;
    EXPECT_FALSE(s.person().tint_face) << name;
  }
}

TEST(Scenes, WallAndSleeveOptionsAreChecked) {
  const Scenario s = Scenario::parse(
      "person: {sleeves: long, tint_face: true}\n"
      "wall: {distance_m: 2.5, bgr: [10, 20, 30], texture: plaster, width_m: 3, height_m: 2.2, shading: 0}\n"
      "keyframes: [{t: 0}]\n", "x.yaml");
  EXPECT_TRUE(s.person().long_sleeves);
  EXPECT_TRUE(s.person().tint_face);
  EXPECT_DOUBLE_EQ(s.wall().distance_m, 2.5);
  EXPECT_EQ(s.wall().bgr, (std::array<int, 3>{{10, 20, 30}}));
  EXPECT_DOUBLE_EQ(s.wall().width_m, 3.0);
  EXPECT_DOUBLE_EQ(s.wall().height_m, 2.2);
  EXPECT_DOUBLE_EQ(s.wall().shading, 0.0);
  const auto error_of = [](const std::string& yaml) {
    try {
      Scenario::parse(yaml + "keyframes: [{t: 0}]\n", "bad.yaml");
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  };
  EXPECT_NE(error_of("wall: {texture: marble}\n").find("wall.texture"), std::string::npos);
  EXPECT_NE(error_of("wall: {distance_m: 0}\n").find("wall.distance_m"), std::string::npos);
  EXPECT_NE(error_of("wall: {colour: [1, 2, 3]}\n").find("wall.colour"), std::string::npos);
  EXPECT_NE(error_of("person: {sleeves: none}\n").find("person.sleeves"), std::string::npos);
  EXPECT_NE(error_of("person: {tint_face: maybe}\n").find("person.tint_face"), std::string::npos);
}

// GIVEN a flat, evenly lit wall 2 m wide and 2.5 m high, 1 m behind a person 3 m in front of the camera
// (camera 1.5 m up, f = 554.256 px): the wall is 4 m away, its sides at x = 320 ± 554.256 / 4 = 320 ± 138.6 px,
// its top at y = 240 - 554.256 (2.5 - 1.5) / 4 = 101.4 px and its foot on the ground at 240 + 554.256 1.5 / 4
// = 447.8 px (below it, the photo: the world has no floor).
TEST(Scenes, TheWallIsWhereItShouldBeAndThePersonOccludesIt) {
  const Scenario s = Scenario::parse(
      "background_grade: {saturation: 1, red_gain: 1, blue_gain: 1, blur_sigma: 0}\n"
      "wall: {distance_m: 1.0, bgr: [90, 140, 200], texture: flat, width_m: 2.0, height_m: 2.5, shading: 0}\n"
      "keyframes: [{t: 0, gesture: REST}]\n", "flat-wall.yaml");
  const SyntheticWorld w(SyntheticParams{}, s, 3);
  cv::Mat labels;
  const SyntheticFrame f = w.render(0.5, 0, std::nullopt, &labels);
  const auto wall_at = [&](int x, int y) { return labels.at<uchar>(y, x) == static_cast<uchar>(PartLabel::Wall); };
  // THEN inside its edges (a few pixels in) it is the wall, in the wall's colour exactly; outside, the photo
  for (const cv::Point p : {cv::Point(185, 120), cv::Point(455, 120), cv::Point(185, 440), cv::Point(455, 440), cv::Point(320, 108)}) {
    SCOPED_TRACE(::testing::Message() << p);
    EXPECT_TRUE(wall_at(p.x, p.y));
    EXPECT_EQ(f.bgr.at<cv::Vec3b>(p), cv::Vec3b(90, 140, 200));
  }
  for (const cv::Point p : {cv::Point(176, 200), cv::Point(464, 200), cv::Point(320, 95), cv::Point(20, 300), cv::Point(200, 455)}) {
    SCOPED_TRACE(::testing::Message() << p);
    EXPECT_FALSE(wall_at(p.x, p.y));
    EXPECT_EQ(labels.at<uchar>(p), static_cast<uchar>(PartLabel::Background));
  }
  // the person stands in front of it: at the body centre, the shirt, not the wall
  EXPECT_EQ(label_at(labels, f.truth.body_centre), static_cast<uchar>(PartLabel::Torso));
  const cv::Vec3b shirt = f.bgr.at<cv::Vec3b>(cv::Point(f.truth.body_centre));
  EXPECT_GT(cv::norm(cv::Vec3d(shirt) - cv::Vec3d(90, 140, 200)), 60.0);
  // and a skin-coloured ball 2 m behind the person is hidden where the wall is
  const Scenario with_ball = Scenario::parse(
      "wall: {distance_m: 1.0, texture: flat, shading: 0}\n"
      "distractor: {left: 0.5, up: 1.5, behind: 2.0}\n"
      "keyframes: [{t: 0, distractor: true}]\n", "ball.yaml");
  cv::Mat ball_labels;
  SyntheticWorld(SyntheticParams{}, with_ball, 3).render(0.5, 0, std::nullopt, &ball_labels);
  EXPECT_EQ(cv::countNonZero(ball_labels == static_cast<uchar>(PartLabel::Distractor)), 0);
}

TEST(Scenes, TheWarmWallFillsTheViewIsTexturedAndMostlySkinToTheUciModel) {
  const SyntheticWorld w(SyntheticParams{}, Scenario::load("warm-wall"), 5);
  cv::Mat labels, mask;
  const SyntheticFrame f = w.render(time_of(w.scenario(), ground_truth_t::GESTURE_REST), 0, std::nullopt, &labels);
  // GIVEN the frame at rest: every pixel is the wall or the person
  EXPECT_EQ(cv::countNonZero(labels == static_cast<uchar>(PartLabel::Background)), 0);
  // THEN at known places beside and above the person (15 x 15 patches) the wall's colour range: its base
  // colour [118, 160, 205] times board tone, grain and shading (0.55 .. 1.1), red > green > blue
  for (const cv::Point p : {cv::Point(40, 60), cv::Point(600, 60), cv::Point(40, 420), cv::Point(600, 420), cv::Point(320, 20),
                            cv::Point(200, 300), cv::Point(440, 300)}) {
    SCOPED_TRACE(::testing::Message() << p);
    const cv::Rect patch(p.x - 7, p.y - 7, 15, 15);
    EXPECT_EQ(cv::countNonZero(labels(patch) == static_cast<uchar>(PartLabel::Wall)), patch.area());
    const cv::Scalar m = cv::mean(f.bgr(patch));
    const double base[3] = {118, 160, 205};
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(m[c], 0.55 * base[c]);
      EXPECT_LT(m[c], 1.1 * base[c]);
    }
    EXPECT_GT(m[2], m[1]);
    EXPECT_GT(m[1], m[0]);
  }
  // textured, not flat: the wall's pixels vary (boards, grain, joints, light)
  cv::Scalar mean, dev;
  cv::meanStdDev(f.bgr, mean, dev, labels == static_cast<uchar>(PartLabel::Wall));
  EXPECT_GT(dev[1], 8.0);
  // and to the project's skin model most of it is skin, but not all (the joints and the darkest grain are not)
  skin().classify(f.bgr, mask);
  const cv::Mat wall = labels == static_cast<uchar>(PartLabel::Wall);
  const double wall_skin = static_cast<double>(cv::countNonZero(mask & wall)) / cv::countNonZero(wall);
  RecordProperty("wall_skin_fraction", std::to_string(wall_skin));
  std::printf("warm-wall: %.1f %% of the wall's pixels are skin to the UCI model\n", 100 * wall_skin);
  EXPECT_GT(wall_skin, 0.5);
  EXPECT_LT(wall_skin, 0.98);
  // the wall is the same whatever the seed (only per-frame nuisances use it), and renders are repeatable
  const SyntheticWorld other(SyntheticParams{}, Scenario::load("warm-wall"), 6);
  EXPECT_EQ(cv::norm(f.bgr, other.render(time_of(w.scenario(), ground_truth_t::GESTURE_REST), 0, std::nullopt).bgr, cv::NORM_INF), 0.0);
}

TEST(Scenes, TheWallMovesWithParallaxInTheClosedLoop) {
  const SyntheticWorld w(SyntheticParams{}, Scenario::parse(
      "wall: {distance_m: 1.0, texture: flat, width_m: 2.0, shading: 0}\nkeyframes: [{t: 0}]\n", "x.yaml"), 1);
  // GIVEN the drone 1 m closer: the wall is 3 m away, its sides at 320 ± 554.256 / 3 = 320 ± 184.8 px
  cv::Mat labels;
  w.render(0.5, 0, CameraPose{1.0, 0.0, -1.5, 0.0}, &labels);
  const auto wall_at = [&](int x) { return labels.at<uchar>(470, x) == static_cast<uchar>(PartLabel::Wall); };
  EXPECT_TRUE(wall_at(140));
  EXPECT_FALSE(wall_at(130));
  EXPECT_TRUE(wall_at(500));
  EXPECT_FALSE(wall_at(510));
}

// Pixels along the forearm, between the true elbow and wrist (a quarter, half and three quarters of the way).
std::vector<cv::Point2f> forearm_points(const cv::Point2f& elbow, const cv::Point2f& wrist) {
  return {elbow + 0.25f * (wrist - elbow), elbow + 0.5f * (wrist - elbow), elbow + 0.75f * (wrist - elbow)};
}

TEST(Scenes, ShortSleevesShowSkinForearmsLongSleevesCoverThem) {
  const Scenario ww = Scenario::load("warm-wall");
  const double t_out = time_of(ww, ground_truth_t::GESTURE_OUT), t_rest = time_of(ww, ground_truth_t::GESTURE_REST);
  const SyntheticWorld w(SyntheticParams{}, ww, 5);
  for (double t : {t_out, t_rest}) {
    cv::Mat labels;
    const SyntheticFrame f = w.render(t, 0, std::nullopt, &labels);
    for (auto [elbow, wrist, label] : {std::tuple{f.truth.right_elbow, f.truth.right_wrist, PartLabel::RightArmSkin},
                                       std::tuple{f.truth.left_elbow, f.truth.left_wrist, PartLabel::LeftArmSkin}}) {
      ASSERT_GT(cv::norm(wrist - elbow), 10.0);  // a forearm of 0.26 m at 3 m: about 48 px
      for (const cv::Point2f& p : forearm_points(elbow, wrist)) {
        SCOPED_TRACE(::testing::Message() << "t " << t << " at " << p);
        const cv::Vec3b c = f.bgr.at<cv::Vec3b>(cv::Point(p));
        // THEN the forearm is bare skin of the light tone (BGR about 166, 186, 226), skin to the model
        EXPECT_EQ(label_at(labels, p), static_cast<uchar>(label));
        EXPECT_NEAR(c[0], 166, 12);
        EXPECT_NEAR(c[1], 186, 12);
        EXPECT_NEAR(c[2], 226, 12);
        EXPECT_TRUE(skin().is_skin(c[0], c[1], c[2]));
      }
    }
  }
  // GIVEN the same person in long sleeves: the same points are shirt, and not skin
  const SyntheticWorld longs(SyntheticParams{}, Scenario::parse(
      "person: {sleeves: long}\nkeyframes: [{t: 0, gesture: OUT, right_arm: out}]\n", "long.yaml"), 5);
  cv::Mat labels;
  const SyntheticFrame f = longs.render(1.0, 0, std::nullopt, &labels);
  for (const cv::Point2f& p : forearm_points(f.truth.right_elbow, f.truth.right_wrist)) {
    SCOPED_TRACE(::testing::Message() << p);
    EXPECT_EQ(label_at(labels, p), static_cast<uchar>(PartLabel::Sleeve));
    const cv::Vec3b c = f.bgr.at<cv::Vec3b>(cv::Point(p));
    EXPECT_FALSE(skin().is_skin(c[0], c[1], c[2]));
  }
  EXPECT_EQ(cv::countNonZero(labels == static_cast<uchar>(PartLabel::RightArmSkin)), 0);
  EXPECT_GT(cv::countNonZero(labels == static_cast<uchar>(PartLabel::RightHand)), 100);
}

TEST(Scenes, TheDarkToneIsDarkerThanTheLightOneHandsAndFace) {
  const Scenario tour = Scenario::load("tour"), dark = Scenario::load("dark-skin");
  const SyntheticWorld light_w(SyntheticParams{}, tour, 1), dark_w(SyntheticParams{}, dark, 1);
  cv::Mat ll, dl;
  const SyntheticFrame lf = light_w.render(time_of(tour, ground_truth_t::GESTURE_REST), 0, std::nullopt, &ll);
  const SyntheticFrame df = dark_w.render(time_of(dark, ground_truth_t::GESTURE_REST), 0, std::nullopt, &dl);
  // THEN the hands' mean luminance: light about 195, dark about 96 (data/skin/synthetic_skin_tones.csv)
  const double light_hands = mean_luma(lf.bgr, ll, {PartLabel::RightHand, PartLabel::LeftHand});
  const double dark_hands = mean_luma(df.bgr, dl, {PartLabel::RightHand, PartLabel::LeftHand});
  std::printf("hand luminance: light %.1f, dark %.1f\n", light_hands, dark_hands);
  EXPECT_NEAR(light_hands, 195, 10);
  EXPECT_NEAR(dark_hands, 96, 10);
  // the dark hands are still skin to the UCI model (the tone is made of UCI skin pixels)
  cv::Mat mask;
  skin().classify(df.bgr, mask);
  const cv::Mat hands = (dl == static_cast<uchar>(PartLabel::RightHand)) | (dl == static_cast<uchar>(PartLabel::LeftHand));
  EXPECT_GT(cv::countNonZero(mask & hands), 0.8 * cv::countNonZero(hands));
  // the tinted face inside the true face box is darker too, and about as dark as the hands
  const cv::Rect box = cv::Rect(df.truth.face_box) & cv::Rect(0, 0, 640, 480);
  const cv::Mat light_face = ll(box) == static_cast<uchar>(PartLabel::Head), dark_face = dl(box) == static_cast<uchar>(PartLabel::Head);
  const auto face_luma = [&](const cv::Mat& bgr, const cv::Mat& m) {
    cv::Mat grey;
    cv::cvtColor(bgr(box), grey, cv::COLOR_BGR2GRAY);
    return cv::mean(grey, m)[0];
  };
  const double lfl = face_luma(lf.bgr, light_face), dfl = face_luma(df.bgr, dark_face);
  std::printf("face luminance: light %.1f, dark (tinted) %.1f\n", lfl, dfl);
  EXPECT_LT(dfl, lfl - 50);
  EXPECT_NEAR(dfl, dark_hands, 30);
}

TEST(Scenes, TheNuisancesBackdropIsThePhotoAsShot) {
  const Scenario s = Scenario::load("nuisances");
  const BackgroundGrade& g = s.background_grade();
  EXPECT_DOUBLE_EQ(g.saturation, 1.0);
  EXPECT_DOUBLE_EQ(g.red_gain, 1.0);
  EXPECT_DOUBLE_EQ(g.blue_gain, 1.0);
  EXPECT_DOUBLE_EQ(g.blur_sigma, 0.0);
  // GIVEN the first second (no light change, no noise): the background pixels' mean colour and saturation
  // are those of home.jpg as shot, not the muted, cool default grade's
  cv::Mat labels;
  const SyntheticFrame f = SyntheticWorld(SyntheticParams{}, s, 1).render(1.0, 0, std::nullopt, &labels);
  const cv::Mat bg = labels == static_cast<uchar>(PartLabel::Background);
  const cv::Mat photo = cv::imread(resolve_project_path("data/backgrounds/home.jpg"));
  ASSERT_FALSE(photo.empty());
  cv::Mat hsv_frame, hsv_photo;
  cv::cvtColor(f.bgr, hsv_frame, cv::COLOR_BGR2HSV);
  cv::cvtColor(photo, hsv_photo, cv::COLOR_BGR2HSV);
  const double sat_frame = cv::mean(hsv_frame, bg)[1], sat_photo = cv::mean(hsv_photo)[1];
  std::printf("saturation: frame background %.1f, photo %.1f\n", sat_frame, sat_photo);
  // (the frame shows the middle 2/3 of the photo's height: its means differ a little from the whole photo's)
  EXPECT_NEAR(sat_frame, sat_photo, 0.15 * sat_photo);
  const Scenario graded = Scenario::parse("background: data/backgrounds/home.jpg\nkeyframes: [{t: 0}]\n", "graded.yaml");
  cv::Mat graded_hsv;
  cv::cvtColor(SyntheticWorld(SyntheticParams{}, graded, 1).render(1.0, 0, std::nullopt).bgr, graded_hsv, cv::COLOR_BGR2HSV);
  EXPECT_LT(cv::mean(graded_hsv, bg)[1], 0.8 * sat_frame);  // the default grade would have muted it (0.7x)
}

}  // namespace
}  // namespace gpilot
