// Known answers of gpilot-eval-tracker's occluder (--occlude): which frames and pixels it paints, with what,
// and which specs it refuses.
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "occluder.hpp"

namespace gpilot {
namespace {

// n frames of 20x30 (BGR, or one channel), frame i filled with value i, truth (5, 6, 4, 4) on each.
class ConstantFrames : public FrameSource {
 public:
  explicit ConstantFrames(int n, int type = CV_8UC3) : n_(n), type_(type) {}
  bool next(EvalFrame& out) override {
    if (i_ >= n_) return false;
    ++i_;
    out.image = cv::Mat(20, 30, type_, cv::Scalar::all(i_));
    out.truth = cv::Rect2d(5, 6, 4, 4);
    return true;
  }
  std::string name() const override { return "constant"; }

 private:
  int n_, type_, i_ = 0;
};

TEST(EvalOccluder, ParsesRectanglesAndFrameRanges) {
  auto o = parse_occluder("1,2,3,4");
  ASSERT_TRUE(o);
  EXPECT_EQ(o->rect, cv::Rect(1, 2, 3, 4));
  EXPECT_EQ(o->first, 1);
  EXPECT_EQ(o->last, 0);
  o = parse_occluder("1,2,3,4@5-9");
  ASSERT_TRUE(o);
  EXPECT_EQ(o->first, 5);
  EXPECT_EQ(o->last, 9);
  o = parse_occluder("1,2,3,4@5-");
  ASSERT_TRUE(o);
  EXPECT_EQ(o->first, 5);
  EXPECT_EQ(o->last, 0);
  for (const char* bad : {"1,2,3", "1,2,0,4", "1,2,3,4@", "1,2,3,4@5", "1,2,3,4@0-3", "1,2,3,4@9-5", "1,2,3,4@5-x", "1,2,3,4@-5"})
    EXPECT_FALSE(parse_occluder(bad)) << bad;
}

TEST(EvalOccluder, PaintsItsFramesOnlyWithTheTextureResizedAndClippedTruthUnchanged) {
  // A texture of two halves (left 200, right 100) the size of a 10x4 rectangle that sticks out of the frame's
  // right edge by 4 px; painted on frames 2-3 of 4.
  cv::Mat texture(4, 10, CV_8UC3, cv::Scalar::all(100));
  texture.colRange(0, 5).setTo(cv::Scalar::all(200));
  auto src = occluded(std::make_unique<ConstantFrames>(4), {*parse_occluder("24,10,10,4@2-3")}, texture);
  EXPECT_EQ(src->name(), "constant (occluded)");
  EvalFrame f;
  for (int i = 1; i <= 4; ++i) {
    ASSERT_TRUE(src->next(f));
    ASSERT_EQ(f.image.size(), cv::Size(30, 20));
    EXPECT_EQ(*f.truth, cv::Rect2d(5, 6, 4, 4));
    const bool painted = i == 2 || i == 3;
    // Left of the rectangle and above it: the frame's own value.
    EXPECT_EQ(f.image.at<cv::Vec3b>(12, 23)[0], i);
    EXPECT_EQ(f.image.at<cv::Vec3b>(9, 26)[0], i);
    // The texture's left half at the rectangle's left, its right half up to the frame's edge.
    EXPECT_EQ(f.image.at<cv::Vec3b>(12, 24)[0], painted ? 200 : i) << "frame " << i;
    EXPECT_EQ(f.image.at<cv::Vec3b>(13, 29)[0], painted ? 100 : i) << "frame " << i;
  }
  EXPECT_FALSE(src->next(f));
}

TEST(EvalOccluder, ATextureIsResizedToTheRectangleWithoutOneMidGrey) {
  auto src = occluded(std::make_unique<ConstantFrames>(1), {*parse_occluder("0,0,8,6")}, cv::Mat(3, 3, CV_8UC3, cv::Scalar(10, 20, 30)));
  EvalFrame f;
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(f.image.at<cv::Vec3b>(5, 7), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(f.image.at<cv::Vec3b>(6, 8)[0], 1);
  src = occluded(std::make_unique<ConstantFrames>(1), {*parse_occluder("0,0,2,2")}, cv::Mat());
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(f.image.at<cv::Vec3b>(1, 1), cv::Vec3b(128, 128, 128));
  EXPECT_EQ(f.image.at<cv::Vec3b>(2, 2)[0], 1);
  EXPECT_THROW(occluded(nullptr, {}, cv::Mat()), std::invalid_argument);
  EXPECT_THROW(occluded(std::make_unique<ConstantFrames>(1), {}, cv::Mat(2, 2, CV_8UC1)), std::invalid_argument);
}

// A one-channel frame (a monochrome camera's log) gets the texture in grey; two occluders both paint it.
TEST(EvalOccluder, AOneChannelFrameGetsTheTextureInGreyEveryOccluderPainted) {
  auto src = occluded(std::make_unique<ConstantFrames>(1, CV_8UC1), {*parse_occluder("0,0,2,2"), *parse_occluder("10,10,2,2")},
                      cv::Mat(2, 2, CV_8UC3, cv::Scalar(50, 50, 50)));
  EvalFrame f;
  ASSERT_TRUE(src->next(f));
  ASSERT_EQ(f.image.type(), CV_8UC1);
  EXPECT_EQ(f.image.at<uchar>(1, 1), 50);
  EXPECT_EQ(f.image.at<uchar>(11, 11), 50);
  EXPECT_EQ(f.image.at<uchar>(5, 5), 1);
}

}  // namespace
}  // namespace gpilot
