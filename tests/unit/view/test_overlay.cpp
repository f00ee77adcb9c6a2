// The drawing core: red marks at the pixels the messages give, cross vs circle, HUD strip, hooks.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "overlay.hpp"
#include "synthetic_run.hpp"

namespace gpilot {
namespace {

const cv::Size kSize(320, 240);
constexpr int64_t kSeq = 7;

bool is_red(const cv::Mat& img, int x, int y) { return img.at<cv::Vec3b>(y, x) == cv::Vec3b(0, 0, 255); }
bool is_colour(const cv::Mat& img, int x, int y, const cv::Scalar& c) {
  return img.at<cv::Vec3b>(y, x) == cv::Vec3b(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
}

class OverlayTest : public ::testing::Test {
 protected:
  void SetUp() override {
    frame = cv::Mat(kSize, CV_8UC3, cv::Scalar(128, 128, 128));
    msgs.track = test::track_of(run, kSeq);
    msgs.hand = test::hand_of(run, kSeq);
    msgs.cmd = test::cmd_of(run, kSeq);
    options.hud = false;
  }
  cv::Mat draw() { return draw_overlay(frame, kSeq, msgs, hud, options); }
  void set_mode(int8_t mode) {
    run.decided_mode = [mode](int64_t) { return mode; };
    msgs.cmd = test::cmd_of(run, kSeq);
  }

  test::SyntheticRun run;
  cv::Mat frame;
  FrameMessages msgs;
  HudState hud;
  OverlayOptions options;
};

TEST_F(OverlayTest, UserBoxIsRedOnItsEdgesOnly) {
  // GIVEN a tracked box; WHEN drawn; THEN its four edges are red and its inside is untouched.
  const cv::Rect2f b = test::user_box_of(kSeq);
  const cv::Mat img = draw();
  const int x0 = static_cast<int>(b.x), y0 = static_cast<int>(b.y);
  const int x1 = x0 + static_cast<int>(b.width) - 1, y1 = y0 + static_cast<int>(b.height) - 1;
  EXPECT_TRUE(is_red(img, x0, 150));
  EXPECT_TRUE(is_red(img, x1, 150));
  EXPECT_TRUE(is_red(img, x0 + 30, y0));
  EXPECT_TRUE(is_red(img, x0 + 30, y1));
  EXPECT_FALSE(is_red(img, x0 + 20, 150));
  EXPECT_FALSE(is_red(img, x0 - 4, 150));
  EXPECT_EQ(img.size(), kSize);  // no HUD strip asked for
}

TEST_F(OverlayTest, HandSquareIsRed) {
  const cv::Rect2f h = test::hand_box_of(kSeq);
  const cv::Mat img = draw();
  EXPECT_TRUE(is_red(img, static_cast<int>(h.x), static_cast<int>(h.y + 10)));
  EXPECT_TRUE(is_red(img, static_cast<int>(h.x + h.width - 1), static_cast<int>(h.y + 10)));
  EXPECT_FALSE(is_red(img, static_cast<int>(h.x + 10), static_cast<int>(h.y + 10)));
}

TEST_F(OverlayTest, FineArrowRunsFromShoulderCentreAlongTheCommandVector) {
  set_mode(gesture_cmd_t::MODE_FINE);
  const cv::Point2f uc = test::shoulder_centre_of(kSeq);
  const float w = test::user_box_of(kSeq).width;
  const cv::Point tip(cvRound(uc.x + test::kFineDirection[0] * w), cvRound(uc.y + test::kFineDirection[1] * w));
  const auto mark = command_mark(msgs);
  ASSERT_TRUE(mark.has_value());
  EXPECT_NEAR(mark->tip.x, uc.x + 48.0f, 1e-3);
  EXPECT_NEAR(mark->tip.y, uc.y - 8.0f, 1e-3);
  const cv::Mat img = draw();
  EXPECT_TRUE(is_red(img, tip.x, tip.y));
  EXPECT_TRUE(is_red(img, cvRound(uc.x), cvRound(uc.y)));
  EXPECT_TRUE(is_red(img, cvRound(uc.x + 24), cvRound(uc.y - 4)));  // half way
  EXPECT_FALSE(is_red(img, cvRound(uc.x - 24), cvRound(uc.y + 4)));  // the other way
}

TEST_F(OverlayTest, UpArrowPointsStraightUp) {
  set_mode(gesture_cmd_t::MODE_UP);  // direction (0, -0.5): 40 px up for an 80 px box
  const cv::Point2f uc = test::shoulder_centre_of(kSeq);
  const cv::Mat img = draw();
  EXPECT_TRUE(is_red(img, cvRound(uc.x), cvRound(uc.y - 40)));
  EXPECT_TRUE(is_red(img, cvRound(uc.x), cvRound(uc.y - 20)));
  EXPECT_FALSE(is_red(img, cvRound(uc.x), cvRound(uc.y + 20)));
}

TEST_F(OverlayTest, CloserIsACrossAndFurtherASmallCircle) {
  const cv::Point2f uc = test::shoulder_centre_of(kSeq);
  const int x = cvRound(uc.x), y = cvRound(uc.y);
  const int s = 10;  // cross half-size: box width / 8
  const int r = 7;   // circle radius: box width / 12, rounded

  set_mode(gesture_cmd_t::MODE_CLOSER);
  cv::Mat img = draw();
  EXPECT_TRUE(is_red(img, x, y));          // the cross goes through p_uc
  EXPECT_TRUE(is_red(img, x + s, y + s));  // and out to its four corners
  EXPECT_TRUE(is_red(img, x - s, y - s));
  EXPECT_TRUE(is_red(img, x + s, y - s));
  EXPECT_FALSE(is_red(img, x + r, y));     // nothing where the circle would be

  set_mode(gesture_cmd_t::MODE_FURTHER);
  img = draw();
  EXPECT_FALSE(is_red(img, x, y));  // a ring: empty in the middle
  EXPECT_TRUE(is_red(img, x + r, y));
  EXPECT_TRUE(is_red(img, x - r, y));
  EXPECT_TRUE(is_red(img, x, y - r));
  EXPECT_FALSE(is_red(img, x + s, y + s));  // no cross corners
}

TEST_F(OverlayTest, HoverDrawsNoCommandMark) {
  set_mode(gesture_cmd_t::MODE_HOVER);
  const cv::Point2f uc = test::shoulder_centre_of(kSeq);
  const cv::Mat img = draw();
  EXPECT_FALSE(is_red(img, cvRound(uc.x), cvRound(uc.y)));
}

TEST_F(OverlayTest, NoCommandMarkWithoutTheFramesHandObservation) {
  msgs.hand.reset();
  EXPECT_FALSE(command_mark(msgs).has_value());
  msgs.hand = test::hand_of(run, kSeq);
  msgs.cmd.reset();
  EXPECT_FALSE(command_mark(msgs).has_value());
}

TEST_F(OverlayTest, LostTrackIsAmberAndSearchingHasNoBox) {
  msgs.track->status = user_track_t::STATUS_LOST;
  const cv::Rect2f b = test::user_box_of(kSeq);
  cv::Mat img = draw();
  EXPECT_TRUE(is_colour(img, static_cast<int>(b.x), 150, kLostAmber));
  msgs.track->status = user_track_t::STATUS_SEARCHING;
  msgs.hand.reset();
  img = draw();
  EXPECT_FALSE(is_red(img, static_cast<int>(b.x), 150));
  EXPECT_FALSE(is_colour(img, static_cast<int>(b.x), 150, kLostAmber));
}

// A user the tracker finds turned away (no command is read from them): the box's label says so, after the mode.
TEST_F(OverlayTest, AUserTurnedAwayIsSaidInTheBoxLabel) {
  const cv::Rect2f b = test::user_box_of(kSeq);
  const auto label_pixels = [&] {
    const cv::Mat img = draw();
    const int bottom = std::max(14, static_cast<int>(b.y));  // the label sits above the box (at 12 px or lower)
    int n = 0;
    for (int y = 0; y < bottom; ++y)
      for (int x = static_cast<int>(b.x); x < img.cols; ++x) {
        const cv::Vec3b& p = img.at<cv::Vec3b>(y, x);
        n += p[2] > 150 && p[1] < 100 && p[0] < 100;  // the text's red, anti-aliased
      }
    return n;
  };
  const int toward = label_pixels();
  msgs.track->facing = user_track_t::FACING_AWAY;
  const int away = label_pixels();
  EXPECT_GT(toward, 0) << "no label to compare with";
  EXPECT_GT(away, 2 * toward) << "the label did not grow by ' (turned away)'";
}

TEST_F(OverlayTest, FaceBoxIsAThinRedBoxOnlyWhenTheTrackCarriesOne) {
  // GIVEN a track without a face (all zero): nothing where a face box would be
  const cv::Rect2f b = test::user_box_of(kSeq);
  const int fx = static_cast<int>(b.x) + 20, fy = static_cast<int>(b.y) + 10, fw = 24, fh = 24;
  cv::Mat img = draw();
  EXPECT_FALSE(is_red(img, fx, fy + 12));
  // WHEN the cascade found a face in this frame: its edges are red, one pixel wide, its inside untouched
  msgs.track->face_box[0] = static_cast<float>(fx);
  msgs.track->face_box[1] = static_cast<float>(fy);
  msgs.track->face_box[2] = static_cast<float>(fw);
  msgs.track->face_box[3] = static_cast<float>(fh);
  img = draw();
  EXPECT_TRUE(is_red(img, fx, fy + 12));
  EXPECT_TRUE(is_red(img, fx + fw - 1, fy + 12));
  EXPECT_TRUE(is_red(img, fx + 12, fy));
  EXPECT_TRUE(is_red(img, fx + 12, fy + fh - 1));
  EXPECT_FALSE(is_red(img, fx + 1, fy + 12));  // thin
  EXPECT_FALSE(is_red(img, fx + 12, fy + 12));
}

TEST_F(OverlayTest, HudStripIsAddedBelowAndLeavesTheFrameAsItWas) {
  const cv::Mat plain = draw();
  options.hud = true;
  hud.vehicle = test::vehicle_of(run, kSeq);
  hud.stage_hz["gpilot-tracker"] = 25.0f;
  const cv::Mat with = draw_overlay(frame, kSeq, msgs, hud, options);
  ASSERT_GT(with.rows, kSize.height);
  EXPECT_EQ(with.rows, kSize.height + hud_height(kSize, options));
  EXPECT_EQ(cv::norm(with(cv::Rect(0, 0, kSize.width, kSize.height)), plain, cv::NORM_INF), 0.0);
  cv::Mat strip;
  cv::cvtColor(with(cv::Rect(0, kSize.height, kSize.width, with.rows - kSize.height)), strip, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(strip > 150), 100);  // there is text
}

TEST_F(OverlayTest, GreyFramesComeOutInColour) {
  cv::Mat grey(kSize, CV_8UC1, cv::Scalar(90));
  const cv::Mat img = draw_overlay(grey, kSeq, msgs, hud, options);
  ASSERT_EQ(img.type(), CV_8UC3);
  EXPECT_TRUE(is_red(img, static_cast<int>(test::user_box_of(kSeq).x), 150));
  EXPECT_EQ(img.at<cv::Vec3b>(5, 5), cv::Vec3b(90, 90, 90));
}

TEST_F(OverlayTest, TruthIsGreenOnlyWhenAsked) {
  msgs.truth = test::truth_of(run, kSeq);
  msgs.truth->user_box[0] = 20;  // away from the red box
  EXPECT_FALSE(is_colour(draw(), 20, 150, kTruthGreen));
  options.truth = true;
  EXPECT_TRUE(is_colour(draw(), 20, 150, kTruthGreen));
}

TEST_F(OverlayTest, SkinMaskHookTintsMaskPixels) {
  options.skin = true;
  options.skin_mask = [](const cv::Mat& f, const FrameMessages&) {
    cv::Mat m = cv::Mat::zeros(f.size(), CV_8UC1);
    m(cv::Rect(0, 0, 10, 10)).setTo(255);
    return m;
  };
  const cv::Mat img = draw();
  EXPECT_NE(img.at<cv::Vec3b>(5, 5), cv::Vec3b(128, 128, 128));
  EXPECT_EQ(img.at<cv::Vec3b>(5, 20), cv::Vec3b(128, 128, 128));
  options.skin = false;
  EXPECT_EQ(draw().at<cv::Vec3b>(5, 5), cv::Vec3b(128, 128, 128));
}

TEST(BoxDrag, DragGivesTheBoxInEitherDirectionAndClipsIt) {
  BoxDrag d;
  d.press(100, 80);
  d.move(120, 90);
  EXPECT_TRUE(d.active());
  auto box = d.release(60, 200, cv::Size(320, 240));
  ASSERT_TRUE(box.has_value());
  EXPECT_EQ(*box, cv::Rect(60, 80, 40, 120));
  d.press(300, 200);
  box = d.release(400, 300, cv::Size(320, 240));
  ASSERT_TRUE(box.has_value());
  EXPECT_EQ(*box, cv::Rect(300, 200, 20, 40));
}

TEST(BoxDrag, AClickIsNotABox) {
  BoxDrag d;
  d.press(100, 80);
  EXPECT_FALSE(d.release(101, 81, cv::Size(320, 240)).has_value());
  EXPECT_FALSE(d.release(150, 150, cv::Size(320, 240)).has_value());  // no press before
}

}  // namespace
}  // namespace gpilot
