// image_t <-> cv::Mat: exact for raw formats, close for JPEG, and a reason for every bad image.
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <turbojpeg.h>

#include "image_codec.hpp"

namespace gpilot {
namespace {

cv::Mat pattern(int w, int h) {
  cv::Mat m(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at<cv::Vec3b>(y, x) = cv::Vec3b(x % 256, y % 256, (x * 7 + y * 3) % 256);
  return m;
}

// The first component's sampling factors in a JPEG's frame header (SOF0): 0x11 for 4:4:4, 0x21 4:2:2, 0x22 4:2:0.
int luma_sampling(const std::vector<uint8_t>& jpeg) {
  for (size_t i = 2; i + 11 < jpeg.size(); ++i)
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) return jpeg[i + 11];  // FF C0, length 2, P 1, Y 2, X 2, Nf 1, C1 1
  return -1;
}

// GIVEN a grey frame with a 2x2 red square on odd pixels (a hand 10 m away is a few pixels)
// WHEN it is encoded with each chroma subsampling
// THEN the header says which, and only 4:4:4 keeps the square red
TEST(ImageCodec, JpegChromaSubsamplingIsChosen) {
  cv::Mat src(32, 32, CV_8UC3, cv::Scalar(128, 128, 128));
  src(cv::Rect(9, 9, 2, 2)).setTo(cv::Scalar(40, 40, 220));
  JpegChroma c{};
  ASSERT_TRUE(jpeg_chroma_from_name("444", c));
  EXPECT_FALSE(jpeg_chroma_from_name("411", c));
  const auto red_error = [&](JpegChroma chroma, int* sampling) {
    const image_t msg = mat_to_image(src, 1, 2, image_t::PIXEL_FORMAT_JPEG, 90, chroma);
    *sampling = luma_sampling(msg.data);
    cv::Mat back;
    EXPECT_EQ(image_to_mat(msg, back), "");
    return cv::norm(back(cv::Rect(9, 9, 2, 2)), src(cv::Rect(9, 9, 2, 2)), cv::NORM_INF);
  };
  int s444 = 0, s422 = 0, s420 = 0;
  const double e444 = red_error(JpegChroma::k444, &s444), e420 = red_error(JpegChroma::k420, &s420);
  red_error(JpegChroma::k422, &s422);
  EXPECT_EQ(s444, 0x11);
  EXPECT_EQ(s422, 0x21);
  EXPECT_EQ(s420, 0x22);
  EXPECT_LT(e444, 30) << "4:4:4 keeps the square's colour";
  EXPECT_GT(e420, 60) << "4:2:0 smears it over its 2x2 chroma blocks";
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

// image_to_mat decodes with libjpeg-turbo's own API; replays of logs made before (and tools that read frames
// with OpenCV) rely on it giving exactly the pixels cv::imdecode gives, for the JPEGs cameras and our capture make:
// 4:2:0, 4:2:2, 4:4:4 and grey, encoded by OpenCV and by other encoders (the photos shipped in data/).
void expect_same_as_imdecode(const std::vector<uint8_t>& bytes, const std::string& what) {
  const cv::Mat ref = cv::imdecode(bytes, cv::IMREAD_COLOR);
  ASSERT_FALSE(ref.empty()) << what;
  image_t msg;
  msg.width = ref.cols;
  msg.height = ref.rows;
  msg.pixel_format = image_t::PIXEL_FORMAT_JPEG;
  msg.data = bytes;
  msg.size = static_cast<int32_t>(bytes.size());
  cv::Mat ours;
  ASSERT_EQ(image_to_mat(msg, ours, ImageLimits{}), "") << what;
  ASSERT_EQ(ours.type(), CV_8UC3) << what;
  EXPECT_EQ(cv::norm(ref, ours, cv::NORM_INF), 0.0) << what;
}

TEST(ImageCodec, JpegPixelsAreExactlyOpenCvs) {
  cv::Mat src(240, 320, CV_8UC3);
  cv::GaussianBlur(pattern(320, 240), src, cv::Size(5, 5), 2);
  std::vector<uint8_t> bytes;
  cv::imencode(".jpg", src, bytes, {cv::IMWRITE_JPEG_QUALITY, 90});
  expect_same_as_imdecode(bytes, "OpenCV's encoder, 4:2:0");
  // TurboJPEG's encoder for the other subsamplings (OpenCV 4.6 cannot choose one).
  tjhandle tj = tjInitCompress();
  ASSERT_NE(tj, nullptr);
  for (int sub : {TJSAMP_420, TJSAMP_422, TJSAMP_444, TJSAMP_GRAY}) {
    for (int q : {50, 95}) {
      unsigned char* jpeg = nullptr;
      unsigned long size = 0;
      ASSERT_EQ(tjCompress2(tj, src.data, src.cols, static_cast<int>(src.step), src.rows, TJPF_BGR, &jpeg, &size, sub, q, 0), 0);
      expect_same_as_imdecode(std::vector<uint8_t>(jpeg, jpeg + size), "subsampling " + std::to_string(sub) + " q" + std::to_string(q));
      tjFree(jpeg);
    }
  }
  tjDestroy(tj);
  int files = 0;
  for (const char* dir : {"data/people", "data/real_people/images"}) {
    for (const auto& f : std::filesystem::directory_iterator(std::filesystem::path(GPILOT_SOURCE_DIR) / dir)) {
      if (f.path().extension() != ".jpg") continue;
      std::ifstream in(f.path(), std::ios::binary);
      expect_same_as_imdecode(std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {}), f.path().filename().string());
      ++files;
    }
  }
  EXPECT_GE(files, 10);
}

TEST(ImageCodec, BadImagesGiveReasons) {
  cv::Mat out;
  image_t jpeg = mat_to_image(pattern(32, 32), 0, 0, image_t::PIXEL_FORMAT_JPEG);
  image_t wrong_dims = jpeg;
  wrong_dims.width = 64;
  EXPECT_EQ(image_to_mat(wrong_dims, out), "JPEG header says 32x32 but the message says 64x32");
  image_t garbage = jpeg;
  for (size_t i = 0; i < garbage.data.size(); ++i) garbage.data[i] = static_cast<uint8_t>(i * 31);
  EXPECT_EQ(image_to_mat(garbage, out), "JPEG data does not start with an SOI marker");
  image_t scan_garbage = jpeg;  // header intact, the scan and its end marker destroyed: libjpeg's verdict
  for (size_t i = scan_garbage.data.size() / 2; i < scan_garbage.data.size(); ++i) scan_garbage.data[i] = 0xFF;
  EXPECT_EQ(image_to_mat(scan_garbage, out), "JPEG data does not decode");
  image_t no_frame = jpeg;
  no_frame.data = {0xFF, 0xD8, 0xFF, 0xDA, 0x00, 0x02, 0xFF, 0xD9};
  no_frame.size = 8;
  EXPECT_EQ(image_to_mat(no_frame, out), "JPEG data has no frame header (SOF) before its scan");
  EXPECT_TRUE(out.empty());
  image_t truncated = mat_to_image(pattern(32, 32), 0, 0);
  truncated.data.resize(100);
  truncated.size = 100;
  EXPECT_EQ(image_to_mat(truncated, out), "image data has 100 bytes, 32x32 needs 3072");
  EXPECT_THROW(mat_to_image(cv::Mat(), 0, 0), std::invalid_argument);
}

// The JPEG bomb: 928 bytes whose frame header says 16384 x 16384 (an 805 MB image). The tracker and
// the hands stage decoded all of it before comparing sizes (tracker output stopped 1.19 s).
image_t jpeg_bomb() {
  image_t m = mat_to_image(pattern(16, 16), 0, 0, image_t::PIXEL_FORMAT_JPEG, 50);
  std::vector<uint8_t>& d = m.data;
  for (size_t i = 2; i + 8 < d.size(); ++i)
    if (d[i] == 0xFF && d[i + 1] == 0xC0) {  // SOF0: FF C0, length, precision, height, width
      d[i + 5] = 0x40, d[i + 6] = 0x00, d[i + 7] = 0x40, d[i + 8] = 0x00;
      break;
    }
  const size_t pad = 928 - d.size() - 4;  // a comment segment after SOI brings it to 928 bytes
  std::vector<uint8_t> com = {0xFF, 0xFE, static_cast<uint8_t>((pad + 2) >> 8), static_cast<uint8_t>((pad + 2) & 0xFF)};
  com.resize(4 + pad, 'x');
  d.insert(d.begin() + 2, com.begin(), com.end());
  m.size = static_cast<int32_t>(d.size());
  m.width = m.height = 16384;
  return m;
}

TEST(ImageCodec, JpegBombIsRejectedFromItsHeader) {
  const image_t bomb = jpeg_bomb();
  ASSERT_EQ(bomb.size, 928);
  int w = 0, h = 0;
  ASSERT_EQ(jpeg_dimensions(bomb.data.data(), bomb.data.size(), w, h), "");
  EXPECT_EQ(w, 16384);
  EXPECT_EQ(h, 16384);
  cv::Mat out;
  // Claimed honestly: beyond the configured maximum, before any pixel is decoded.
  EXPECT_EQ(image_to_mat(bomb, out), "image is 16384x16384, larger than image.max_width x image.max_height (1920x1080)");
  // Claimed as a small frame: the header disagrees, nothing is decoded.
  image_t lying = bomb;
  lying.width = 640;
  lying.height = 480;
  EXPECT_EQ(image_to_mat(lying, out), "JPEG header says 16384x16384 but the message says 640x480");
  EXPECT_TRUE(out.empty());
}

TEST(ImageCodec, LimitsApplyToRawFramesToo) {
  const image_t msg = mat_to_image(pattern(64, 48), 0, 0);
  cv::Mat out;
  ImageLimits small;
  small.max_width = 32;
  EXPECT_EQ(image_to_mat(msg, out, small), "image is 64x48, larger than image.max_width x image.max_height (32x1080)");
  EXPECT_EQ(image_to_mat(msg, out), "");
}

TEST(ImageCodec, JpegDimensionsWalkTheMarkerSegments) {
  const image_t jpeg = mat_to_image(pattern(40, 24), 0, 0, image_t::PIXEL_FORMAT_JPEG);
  int w = 0, h = 0;
  ASSERT_EQ(jpeg_dimensions(jpeg.data.data(), jpeg.data.size(), w, h), "");
  EXPECT_EQ(w, 40);
  EXPECT_EQ(h, 24);
  // Cut inside the first segment after SOI (APP0, 16 bytes + marker): its length runs past the end.
  EXPECT_EQ(jpeg_dimensions(jpeg.data.data(), 10, w, h), "JPEG marker segment runs past the end of the data");
  const uint8_t stray[] = {0xFF, 0xD8, 0x00, 0xFF, 0xC0};
  EXPECT_EQ(jpeg_dimensions(stray, sizeof stray, w, h), "JPEG data has stray bytes before its frame header");
  const uint8_t dnl[] = {0xFF, 0xD8, 0xFF, 0xC0, 0x00, 0x0B, 8, 0, 0, 0, 16, 1, 1, 0x11, 0};
  EXPECT_EQ(jpeg_dimensions(dnl, sizeof dnl, w, h), "JPEG frame header gives no size (a DNL height is not supported)");
}

}  // namespace
}  // namespace gpilot
