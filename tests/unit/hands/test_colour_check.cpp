// A frame without colour (a monochrome or IR camera, a greyscale video) is refused by the hands stage with that
// reason, and teaches its skin model nothing. Sample grid: every 4th pixel in x and y, so a 400 x 400 frame has
// 100 x 100 = 10,000 samples and a 40 x 40 patch at the origin holds 10 x 10 of them (1 %).
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hands/colour_check.hpp"
#include "hands/skin_hand_method.hpp"
#include "hands/hands_service.hpp"
#include "image_codec.hpp"
#include "paths.hpp"

using namespace gpilot;

namespace {

// A grey frame with JPEG-like noise: B, G, R differ by at most 2 (a greyscale JPEG decoded to BGR).
cv::Mat grey_frame(cv::Size size) {
  cv::Mat f(size, CV_8UC3);
  for (int y = 0; y < f.rows; ++y)
    for (int x = 0; x < f.cols; ++x) {
      const uint8_t v = static_cast<uint8_t>((x * 7 + y * 3) % 200 + 20);
      f.at<cv::Vec3b>(y, x) = cv::Vec3b(v, static_cast<uint8_t>(v + (x + y) % 3), static_cast<uint8_t>(v + 1));
    }
  return f;
}

cv::Mat as_grey(const cv::Mat& bgr) {
  cv::Mat g, out;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  cv::cvtColor(g, out, cv::COLOR_GRAY2BGR);
  return out;
}

}  // namespace

TEST(ColourCheck, AGreyFrameHasNoColour) {
  SkinParams p;  // min_chroma 12, min_colour_fraction 0.005
  const cv::Mat f = grey_frame({400, 400});
  EXPECT_EQ(coloured_fraction(f, p.min_chroma), 0.0);
  EXPECT_FALSE(has_colour(f, p));
}

TEST(ColourCheck, AFewColouredPixelsAreNotEnoughAndOnePercentIs) {
  SkinParams p;
  cv::Mat f = grey_frame({400, 400});
  // GIVEN a skin-coloured 20 x 20 patch: 5 x 5 = 25 of 10,000 samples (0.25 %, under 0.5 %)
  f(cv::Rect(0, 0, 20, 20)).setTo(cv::Scalar(90, 120, 170));
  EXPECT_DOUBLE_EQ(coloured_fraction(f, p.min_chroma), 0.0025);
  EXPECT_FALSE(has_colour(f, p));
  // WHEN the patch is 40 x 40: 100 samples, 1 %
  f(cv::Rect(0, 0, 40, 40)).setTo(cv::Scalar(90, 120, 170));
  EXPECT_DOUBLE_EQ(coloured_fraction(f, p.min_chroma), 0.01);
  EXPECT_TRUE(has_colour(f, p));
  // a chroma of 11 (under min_chroma 12) is grey
  f(cv::Rect(0, 0, 40, 40)).setTo(cv::Scalar(100, 105, 111));
  EXPECT_FALSE(has_colour(f, p));
  // and the check off accepts anything
  p.min_colour_fraction = 0;
  EXPECT_TRUE(has_colour(f, p));
}

TEST(ColourCheck, TheObserverRefusesAGreyPhotoAndLearnsNothingFromIt) {
  HandsParams p;
  SkinHandMethod observer(p, SkinModel::load(resolve_project_path(p.skin.model)));
  const cv::Mat photo = cv::imread(resolve_project_path("data/people/messi5.jpg"));
  ASSERT_FALSE(photo.empty());
  UserView user;
  user.box = cv::Rect2f(200, 30, 120, 300);
  user.face = cv::Rect2f(226, 93, 40, 40);  // the face, as in test_face_detector.cpp
  user.track_id = 1;
  // GIVEN the photo in grey THEN nothing is looked for and nothing learnt
  HandResult r = observer.detect(as_grey(photo), user);
  EXPECT_TRUE(r.colourless);
  EXPECT_EQ(r.kind, HandKind::None);
  EXPECT_EQ(r.skin_inside + r.skin_outside, 0);
  EXPECT_EQ(observer.adaptation().user_samples, 0);
  EXPECT_EQ(observer.adaptation().scene_samples, 0);
  // WHEN it is in colour THEN the stage runs and learns the scene and the face
  r = observer.detect(photo, user);
  EXPECT_FALSE(r.colourless);
  EXPECT_GT(observer.adaptation().scene_samples, 0);
  EXPECT_GT(observer.adaptation().user_samples, 0);
}

TEST(ColourCheck, TheServiceRejectsAGreyFrameNamingTheCause) {
  HandsParams p;
  SkinHandMethod observer(p, SkinModel::load(resolve_project_path(p.skin.model)));
  const cv::Mat photo = cv::imread(resolve_project_path("data/people/messi5.jpg"));
  ASSERT_FALSE(photo.empty());
  user_track_t track{};
  track.seq = 7;
  track.status = user_track_t::STATUS_TRACKING;
  track.track_id = 1;
  track.image_width = photo.cols;
  track.image_height = photo.rows;
  track.box[0] = 200, track.box[1] = 30, track.box[2] = 120, track.box[3] = 300;
  hand_obs_t obs{};
  const std::string why = hands_on_pair(observer, mat_to_image(as_grey(photo), 0, 7, image_t::PIXEL_FORMAT_BGR8), track,
                                        ImageLimits{}, obs);
  EXPECT_NE(why.find("CAMERA seq 7: skin needs colour, the frame has none"), std::string::npos) << why;
  EXPECT_EQ(hands_on_pair(observer, mat_to_image(photo, 0, 7, image_t::PIXEL_FORMAT_BGR8), track, ImageLimits{}, obs), "");
  EXPECT_EQ(obs.seq, 7);
}
