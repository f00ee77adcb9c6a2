// score_person's "hand shows skin": the skin the stage's own classifier sees in its hand square at the truth hand
// (a third of the forearm beyond the wrist), against the count the stage needs there.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "hands_score.hpp"
#include "test_people.hpp"

namespace gpilot {
namespace {

constexpr int kBins = 32;
const cv::Vec3b kSkin(60, 110, 200);  // B, G, R: the one colour the test classifier calls skin

SkinClassifier one_colour_classifier() {
  std::vector<uint8_t> table(kBins * kBins * kBins, 0);
  table[static_cast<size_t>((kSkin[0] >> 3) * kBins * kBins + (kSkin[1] >> 3) * kBins + (kSkin[2] >> 3))] = 1;
  return SkinClassifier(kBins, std::move(table));
}

// The upright person (test_people.hpp) with the left arm (image right) stretched out sideways: elbow (150,100),
// wrist (180,100), so the hand square's centre is (190,100); the right arm hangs.
PersonKeypointTruth out_person() {
  BodyKeypoints k = test_people::upright();
  test_people::arm(k.left_elbow, k.left_wrist, {150, 100}, {180, 100});
  return keypoint_truth(k);
}

// The stage ran on an 80 px box: its hand square is 20 px, where Alg. 1 needs more than 30 skin pixels.
HandsOutput stage_ran(bool colourless = false) {
  HandsOutput r;
  r.user_box = cv::Rect2f(100, 60, 80, 160);
  if (colourless) r.refused = "no colour";
  return r;
}

cv::Mat with_patch(cv::Point centre, int side) {
  cv::Mat bgr(240, 320, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::rectangle(bgr, cv::Rect(centre.x - side / 2, centre.y - side / 2, side, side), cv::Scalar(kSkin[0], kSkin[1], kSkin[2]),
                cv::FILLED);
  return bgr;
}

TEST(HandsScore, GivenSkinAtTheTruthHandWhenScoredThenItsCountAndShown) {
  const PersonKeypointTruth t = out_person();
  ASSERT_EQ(t.person, PersonTruth::Out);
  EXPECT_EQ(truth_hand_square(t.left, 20), cv::Rect(180, 90, 20, 20));
  const SkinClassifier skin = one_colour_classifier();
  const HandsParams params;
  const PersonScore s = score_person(t, stage_ran(), with_patch({190, 100}, 30), &skin, &params);
  ASSERT_TRUE(s.hand_skin);
  EXPECT_EQ(*s.hand_skin, 400);  // the whole square
  EXPECT_TRUE(s.hand_shows_skin);
}

TEST(HandsScore, GivenTooLittleOrNoSkinThereWhenScoredThenNotShown) {
  const PersonKeypointTruth t = out_person();
  const SkinClassifier skin = one_colour_classifier();
  const HandsParams params;
  // 5 x 5 = 25 pixels: at most the 30 the stage needs; 6 x 6 = 36: more.
  const PersonScore small = score_person(t, stage_ran(), with_patch({190, 100}, 5), &skin, &params);
  EXPECT_EQ(small.hand_skin.value_or(-1), 25);
  EXPECT_FALSE(small.hand_shows_skin);
  const PersonScore enough = score_person(t, stage_ran(), with_patch({190, 100}, 6), &skin, &params);
  EXPECT_EQ(enough.hand_skin.value_or(-1), 36);
  EXPECT_TRUE(enough.hand_shows_skin);
  // Skin at the hanging hand (the REST arm) is not the OUT hand's.
  const PersonScore elsewhere = score_person(t, stage_ran(), with_patch({60, 190}, 30), &skin, &params);
  EXPECT_EQ(elsewhere.hand_skin.value_or(-1), 0);
  EXPECT_FALSE(elsewhere.hand_shows_skin);
  // A photo the stage refused (no colour) shows no skin, whatever the classifier would say.
  const PersonScore refused = score_person(t, stage_ran(true), with_patch({190, 100}, 30), &skin, &params);
  EXPECT_EQ(refused.hand_skin.value_or(-1), 0);
  EXPECT_FALSE(refused.hand_shows_skin);
}

TEST(HandsScore, GivenARestPersonOrNoClassifierWhenScoredThenNotMeasured) {
  const SkinClassifier skin = one_colour_classifier();
  const HandsParams params;
  const PersonKeypointTruth out = out_person();
  EXPECT_FALSE(score_person(out, stage_ran(), with_patch({190, 100}, 30)).hand_skin);
  PersonKeypointTruth rest = out;
  rest.person = PersonTruth::Rest;
  rest.left.label = ArmTruth::Rest;
  EXPECT_FALSE(score_person(rest, stage_ran(), with_patch({190, 100}, 30), &skin, &params).hand_skin);
}

}  // namespace
}  // namespace gpilot
