// The skin model that learns the user (face) and the scene (around the user) on top of the committed table.
// Colours (B, G, R) and what the committed table says of them (level = P(skin) x 255, threshold 0.75 = 191):
//   wall (118, 160, 205): 253, a light pine wall the table calls skin;  hand (90, 120, 170): 247;
//   cheek (40, 48, 164): 134, a red-brown the table is unsure of;      blue (200, 60, 20): ~0;
//   orange (58, 90, 184): > 191, the T-shirt of the man in data/tracking/cf_tracking_sample.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "hands/clothing_colours.hpp"
#include "hands/skin_adapter.hpp"
#include "paths.hpp"

using namespace gpilot;

namespace {

const cv::Scalar kWall(118, 160, 205), kHand(90, 120, 170), kCheek(40, 48, 164), kBlue(200, 60, 20), kOrange(58, 90, 184);

bool skin(SkinAdapter& a, const cv::Scalar& c) {
  return a.classifier_for_frame().is_skin(static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]), static_cast<uint8_t>(c[2]));
}

struct SkinAdapterTest : ::testing::Test {
  SkinParams params;
  SkinModel model = SkinModel::load(resolve_project_path(params.model));
  void SetUp() override {
    ASSERT_TRUE(model.has_likelihoods());
    ASSERT_GT(model.level(118, 160, 205), 191);
    ASSERT_GT(model.level(90, 120, 170), 191);
    ASSERT_EQ(model.level(40, 48, 164), 134);
  }
};

}  // namespace

TEST_F(SkinAdapterTest, AWallThatIsEverywhereAroundTheUserStopsBeingSkinAndTheHandStaysSkin) {
  SkinAdapter a(params, model);
  ASSERT_TRUE(skin(a, kWall));
  // GIVEN a frame of wall with the user's search rectangle in the middle (not learnt from)
  cv::Mat frame(240, 320, CV_8UC3, kWall);
  const cv::Rect search(100, 40, 120, 160);
  frame(search).setTo(kHand);
  // WHEN the scene is learnt THEN the wall is not skin any more, the hand colour still is
  a.learn_scene(frame, search);
  EXPECT_EQ(a.scene_samples(), 80 * 60 - 30 * 40);  // every 4th pixel in x and y, outside the rectangle
  EXPECT_FALSE(skin(a, kWall));
  EXPECT_TRUE(skin(a, kHand));
  EXPECT_GT(a.changed_fraction(), 0.0);
}

TEST_F(SkinAdapterTest, TheUsersFaceMakesTheirOwnToneSkinAndCannotUnmakeOthers) {
  SkinAdapter a(params, model);
  ASSERT_FALSE(skin(a, kCheek));
  // GIVEN a face box whose cheek band (rows 50..85 %, columns 20..80 %) is the user's tone
  cv::Mat frame(240, 320, CV_8UC3, kBlue);
  const cv::Rect2f face(100, 50, 60, 80);
  frame(cv::Rect(100, 50, 60, 80)).setTo(kCheek);
  a.learn_user(frame, face);
  // THEN 36 x 28 band pixels were learnt and the tone is skin; the table's skin colours stay skin
  EXPECT_EQ(a.user_samples(), 36 * 28);
  EXPECT_TRUE(skin(a, kCheek));
  EXPECT_TRUE(skin(a, kHand));
  EXPECT_FALSE(skin(a, kBlue));
}

TEST_F(SkinAdapterTest, AFaceBoxOnBackgroundTeachesNothing) {
  SkinAdapter a(params, model);
  const cv::Mat frame(240, 320, CV_8UC3, kBlue);
  a.learn_user(frame, cv::Rect2f(100, 50, 60, 80));  // the table gives blue P ~ 0: not learnt as skin
  a.learn_user(frame, cv::Rect2f(-500, -500, 10, 10));  // off the image
  EXPECT_EQ(a.user_samples(), 0);
  EXPECT_EQ(a.classifier_for_frame().mask_table(), SkinClassifier(model, params.threshold).mask_table());
}

TEST_F(SkinAdapterTest, ResetGivesTheTableBackAndTheSameInputsGiveTheSameModel) {
  SkinAdapter a(params, model), b(params, model);
  cv::Mat frame(240, 320, CV_8UC3, kWall);
  frame(cv::Rect(100, 50, 60, 80)).setTo(kCheek);
  for (SkinAdapter* s : {&a, &b}) {
    s->learn_user(frame, cv::Rect2f(100, 50, 60, 80));
    s->learn_scene(frame, cv::Rect(90, 40, 80, 160));
  }
  EXPECT_EQ(a.classifier_for_frame().mask_table(), b.classifier_for_frame().mask_table());
  a.reset();
  EXPECT_EQ(a.user_samples() + a.scene_samples(), 0);
  EXPECT_EQ(a.classifier_for_frame().mask_table(), SkinClassifier(model, params.threshold).mask_table());
}

TEST_F(SkinAdapterTest, AShirtTheTableCallsSkinIsTheShirtOnceTheUsersSkinIsKnown) {
  ASSERT_GT(model.level(58, 90, 184), 191);
  SkinAdapter a(params, model);
  ClothingColours clothing(params.adapt, model.bins());
  const auto skin_with_clothing = [&](SkinAdapter& s, const ClothingColours& c, const cv::Scalar& colour) {
    return s.classifier_for_frame(&c).is_skin(static_cast<uint8_t>(colour[0]), static_cast<uint8_t>(colour[1]),
                                              static_cast<uint8_t>(colour[2]));
  };
  // GIVEN a user in an orange shirt with a hand of their own skin in front of it, on a blue scene
  cv::Mat frame(240, 320, CV_8UC3, kBlue);
  const cv::Rect torso(100, 80, 80, 100);
  frame(torso).setTo(kOrange);
  frame(cv::Rect(130, 120, 16, 16)).setTo(kHand);
  // WHEN the torso is learnt before any face THEN the skin model learns nothing: the hand in front could be taken
  // for clothing
  clothing.learn(frame, torso, a.user_skin_colours());
  EXPECT_EQ(clothing.samples(), 0);
  EXPECT_TRUE(skin_with_clothing(a, clothing, kOrange));
  // WHEN the face shows the user's skin (the hand's tone) and the torso is learnt
  frame(cv::Rect(110, 10, 60, 60)).setTo(kHand);
  a.learn_user(frame, cv::Rect2f(110, 10, 60, 60));
  clothing.learn(frame, torso, a.user_skin_colours());
  // THEN the shirt is no longer skin and the hand still is: its colour was kept out of the clothing
  EXPECT_EQ(clothing.samples(), 20 * 25 - 4 * 4);  // every 4th pixel of the torso but the hand's
  EXPECT_FALSE(skin_with_clothing(a, clothing, kOrange));
  EXPECT_TRUE(skin_with_clothing(a, clothing, kHand));
  // AND with clothing_weight 0 the shirt stays skin (the rule off)
  params.adapt.clothing_weight = 0;
  SkinAdapter off(params, model);
  ClothingColours off_clothing(params.adapt, model.bins());
  off.learn_user(frame, cv::Rect2f(110, 10, 60, 60));
  off_clothing.learn(frame, torso, off.user_skin_colours());
  EXPECT_EQ(off_clothing.samples(), 0);
  EXPECT_TRUE(skin_with_clothing(off, off_clothing, kOrange));
}

TEST_F(SkinAdapterTest, OffItIsTheTable) {
  params.adapt.enabled = false;
  SkinAdapter a(params, model);
  const cv::Mat frame(240, 320, CV_8UC3, kWall);
  a.learn_scene(frame, cv::Rect(0, 0, 10, 10));
  EXPECT_TRUE(skin(a, kWall));
  EXPECT_EQ(a.scene_samples(), 0);
}

TEST(SkinModelLikelihoods, SurviveTheFileAndAnOldFileWithoutThemIsRefusedOnlyForAdaptation) {
  SkinHistogram h(4);
  h.add(0, 0, 0, true, 3);
  h.add(255, 255, 255, false, 1);
  const SkinModel m = SkinModel::train(h, {0.0, "test"});
  ASSERT_TRUE(m.has_likelihoods());
  EXPECT_NEAR(m.skin_prior(), 0.75, 1e-12);
  EXPECT_FLOAT_EQ(m.skin_likelihood()[0], 1.0f);
  EXPECT_FLOAT_EQ(m.non_likelihood()[63], 1.0f);
  const std::string path = (std::filesystem::temp_directory_path() / "gpilot_skin_likelihoods.yaml").string();
  m.save(path);
  const SkinModel back = SkinModel::load(path);
  EXPECT_EQ(back.skin_likelihood(), m.skin_likelihood());
  EXPECT_EQ(back.non_likelihood(), m.non_likelihood());
  EXPECT_DOUBLE_EQ(back.skin_prior(), m.skin_prior());
  // An old (format 1) file: the table alone.
  {
    std::ofstream f(path);
    f << "format: gpilot-skin-histogram-1\nbins: 2\ntable_hex: ff00000000000000\n";
  }
  const SkinModel old = SkinModel::load(path);
  EXPECT_FALSE(old.has_likelihoods());
  SkinParams p;
  EXPECT_THROW(SkinAdapter(p, old), SkinModelError);
  p.adapt.enabled = false;
  EXPECT_NO_THROW(SkinAdapter(p, old));
  std::filesystem::remove(path);
}

TEST_F(SkinAdapterTest, ReadingTheClassifierCountsNoFrameAndRebuildsNothing) {
  SkinAdapter a(params, model);
  cv::Mat frame(240, 320, CV_8UC3, kWall);
  const cv::Rect search(100, 40, 120, 160);
  frame(search).setTo(kHand);
  // GIVEN the wall learnt as scene and a frame judged with it: the first state is built at once
  a.learn_scene(frame, search);
  ASSERT_FALSE(a.classifier_for_frame().is_skin(118, 160, 205));
  // WHEN the scene is forgotten in favour of a wall of the hand's colour (the state changes) and the classifier is
  // read more times than adapt.rebuild_frames
  a.reset();
  frame.setTo(kWall);
  a.learn_scene(frame, search);
  a.classifier_for_frame();  // a track's first state: built at once
  cv::Mat hand_wall(240, 320, CV_8UC3, kHand);
  a.learn_scene(hand_wall, search);
  const std::vector<uint8_t> built = a.classifier().mask_table();
  for (int i = 0; i < 3 * params.adapt.rebuild_frames; ++i) EXPECT_EQ(a.classifier().mask_table(), built);
  // THEN nothing was rebuilt; the frames that follow rebuild it after adapt.rebuild_frames of them
  for (int i = 1; i < params.adapt.rebuild_frames; ++i) EXPECT_EQ(a.classifier_for_frame().mask_table(), built) << i;
  EXPECT_NE(a.classifier_for_frame().mask_table(), built);
}
