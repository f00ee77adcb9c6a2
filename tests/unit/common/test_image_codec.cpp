// image_t <-> cv::Mat: exact for raw formats, close for JPEG, and a reason for every bad image.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "image_codec.hpp"

namespace gpilot {
namespace {

cv::Mat pattern(int w, int h) {
  cv::Mat m(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at<cv::Vec3b>(y, x) = cv::Vec3b(x % 256, y % 256, (x * 7 + y * 3) % 256);
  return m;
}

TEST(ImageCodec, BgrRoundTripIsExact) {
  const cv::Mat src = pattern(64, 48);
  const image_t msg = mat_to_image(src, 123, 4);
  EXPECT_EQ(msg.utime, 123);
  EXPECT_EQ(msg.seq, 4);
  EXPECT_EQ(msg.row_stride, 64 * 3);
  EXPECT_EQ(msg.size, 64 * 48 * 3);
  cv::Mat back;
  ASSERT_EQ(image_to_mat(msg, back), "");
  ASSERT_EQ(back.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(src, back, cv::NORM_INF), 0.0);
}

TEST(ImageCodec, RoiWithStrideRoundTrip) {
  const cv::Mat big = pattern(100, 80);
  const cv::Mat roi = big(cv::Rect(10, 5, 33, 21));  // not continuous
  const image_t msg = mat_to_image(roi, 0, 0);
  cv::Mat back;
  ASSERT_EQ(image_to_mat(msg, back), "");
  EXPECT_EQ(cv::norm(roi, back, cv::NORM_INF), 0.0);
}

TEST(ImageCodec, GrayAndPaddedRows) {
  const cv::Mat src = pattern(16, 8);
  image_t msg = mat_to_image(src, 0, 0, image_t::PIXEL_FORMAT_GRAY8);
  cv::Mat grey;
  cv::cvtColor(src, grey, cv::COLOR_BGR2GRAY);
  cv::Mat back;
  ASSERT_EQ(image_to_mat(msg, back), "");
  ASSERT_EQ(back.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(grey, back, cv::NORM_INF), 0.0);
  // A sender with 4 padding bytes per row: decoded by stride.
  image_t padded = msg;
  padded.row_stride = 20;
  padded.data.assign(20 * 8, 0);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) padded.data[y * 20 + x] = grey.at<uint8_t>(y, x);
  padded.size = 160;
  ASSERT_EQ(image_to_mat(padded, back), "");
  EXPECT_EQ(cv::norm(grey, back, cv::NORM_INF), 0.0);
}

TEST(ImageCodec, JpegRoundTripIsClose) {
  cv::Mat src(120, 160, CV_8UC3);
  cv::GaussianBlur(pattern(160, 120), src, cv::Size(9, 9), 3);
  const image_t msg = mat_to_image(src, 1, 2, image_t::PIXEL_FORMAT_JPEG, 95);
  EXPECT_EQ(msg.pixel_format, image_t::PIXEL_FORMAT_JPEG);
  EXPECT_LT(msg.size, 160 * 120 * 3);
  cv::Mat back;
  ASSERT_EQ(image_to_mat(msg, back), "");
  EXPECT_EQ(back.size(), src.size());
  EXPECT_GT(cv::PSNR(src, back), 30.0);
}

TEST(ImageCodec, BadImagesGiveReasons) {
  cv::Mat out;
  image_t jpeg = mat_to_image(pattern(32, 32), 0, 0, image_t::PIXEL_FORMAT_JPEG);
  image_t wrong_dims = jpeg;
  wrong_dims.width = 64;
  EXPECT_EQ(image_to_mat(wrong_dims, out), "JPEG decodes to 32x32 but the message says 64x32");
  image_t garbage = jpeg;
  for (size_t i = 0; i < garbage.data.size(); ++i) garbage.data[i] = static_cast<uint8_t>(i * 31);
  EXPECT_EQ(image_to_mat(garbage, out), "JPEG data does not decode");
  EXPECT_TRUE(out.empty());
  image_t truncated = mat_to_image(pattern(32, 32), 0, 0);
  truncated.data.resize(100);
  truncated.size = 100;
  EXPECT_EQ(image_to_mat(truncated, out), "image data has 100 bytes, 32x32 needs 3072");
  EXPECT_THROW(mat_to_image(cv::Mat(), 0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace gpilot
