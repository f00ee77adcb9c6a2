// The user's clothing colours, learnt once a frame from the torso (ClothingColours): what the arm test reads as
// worn (this frame's torso, a colour on at least 1 in 200 of its pixels) and what the skin model's clothing class
// learns (every 4th pixel, with decay, only with the user's skin colours known and without them).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "hands/clothing_colours.hpp"
#include "hands/skin_model.hpp"

using namespace gpilot;

namespace {

const cv::Vec3b kGreen(60, 140, 40), kRed(40, 40, 200), kBlue(200, 60, 20);
constexpr int kBins = 32;  // the committed skin table's

bool worn(const ClothingColours& c, const cv::Vec3b& colour) { return c.worn(colour.val); }

size_t bin_of(const cv::Vec3b& c) { return static_cast<size_t>(((c[0] >> 3) * kBins + (c[1] >> 3)) * kBins + (c[2] >> 3)); }

}  // namespace

TEST(ClothingColours, AColourOnTheTorsoIsWornAndASpeckOnItOrTheSceneIsNot) {
  ClothingColours c(SkinAdaptParams{}, kBins);
  // GIVEN a blue scene and a green torso of 80 x 100 px with a red speck of 6 x 6 (36 px, under 1 in 200 of 8000)
  cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(kBlue));
  const cv::Rect torso(100, 80, 80, 100);
  frame(torso).setTo(cv::Scalar(kGreen));
  frame(cv::Rect(130, 120, 6, 6)).setTo(cv::Scalar(kRed));
  // WHEN the torso is learnt THEN green is worn, the speck and the scene are not
  c.learn(frame, torso);
  EXPECT_TRUE(worn(c, kGreen));
  EXPECT_FALSE(worn(c, kRed));
  EXPECT_FALSE(worn(c, kBlue));
  // AND a speck of 8 x 5 (40 px, 1 in 200) is worn
  frame(cv::Rect(130, 120, 8, 5)).setTo(cv::Scalar(kRed));
  c.learn(frame, torso);
  EXPECT_TRUE(worn(c, kRed));
  // AND WHEN the next frame's torso is blue THEN only blue is worn: this frame's torso alone
  frame(torso).setTo(cv::Scalar(kBlue));
  c.learn(frame, torso);
  EXPECT_TRUE(worn(c, kBlue));
  EXPECT_FALSE(worn(c, kGreen));
  // AND an empty torso (or one off the image) wears nothing
  c.learn(frame, cv::Rect());
  EXPECT_FALSE(worn(c, kBlue));
  c.learn(frame, cv::Rect(-500, -500, 10, 10));
  EXPECT_FALSE(worn(c, kBlue));
}

TEST(ClothingColours, TheSkinModelsClothingIsLearntOnlyWithTheUsersSkinKnownAndWithoutIt) {
  ClothingColours c(SkinAdaptParams{}, kBins);
  cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(kBlue));
  const cv::Rect torso(100, 80, 80, 100);
  frame(torso).setTo(cv::Scalar(kGreen));
  frame(cv::Rect(100, 80, 40, 100)).setTo(cv::Scalar(kRed));  // the torso's left half: the user's skin colour here
  // GIVEN no skin colours of the user yet WHEN the torso is learnt THEN the histogram learns nothing
  c.learn(frame, torso);
  EXPECT_EQ(c.samples(), 0);
  EXPECT_TRUE(c.histogram().empty());
  // GIVEN red is the user's skin WHEN the torso is learnt THEN every 4th pixel (x, y = 2, 6, 10, ...) of its green
  // half: 10 x 25, all of it green
  std::vector<uint8_t> user_skin(static_cast<size_t>(kBins) * kBins * kBins, 0);
  user_skin[bin_of(kRed)] = 1;
  c.learn(frame, torso, user_skin);
  EXPECT_EQ(c.samples(), 10 * 25);
  ASSERT_EQ(c.histogram().size(), user_skin.size());
  EXPECT_DOUBLE_EQ(c.histogram()[bin_of(kGreen)], 1.0);
  EXPECT_DOUBLE_EQ(c.histogram()[bin_of(kRed)], 0.0);
  // AND the next frame's torso blends in at clothing_rate (0.1)
  frame(torso).setTo(cv::Scalar(kBlue));
  c.learn(frame, torso, user_skin);
  EXPECT_EQ(c.samples(), 10 * 25 + 20 * 25);
  EXPECT_DOUBLE_EQ(c.histogram()[bin_of(kGreen)], 0.9);
  EXPECT_DOUBLE_EQ(c.histogram()[bin_of(kBlue)], 0.1);
  // AND reset forgets it all
  c.reset();
  EXPECT_EQ(c.samples(), 0);
  EXPECT_TRUE(c.histogram().empty());
  EXPECT_FALSE(worn(c, kBlue));
}

TEST(ClothingColours, BinsThatAreNoPowerOfTwoAreRefused) {
  EXPECT_THROW(ClothingColours(SkinAdaptParams{}, 24), SkinModelError);
  EXPECT_NO_THROW(ClothingColours(SkinAdaptParams{}, 32));
}
