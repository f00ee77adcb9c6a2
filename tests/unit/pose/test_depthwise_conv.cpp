// Our depthwise convolution against OpenCV's own on the same layer: one cv::dnn Convolution (with a ReLU6 after
// it or not) set up once in a DepthwiseConvScope and once outside it, on random weights and images, over the
// shapes BlazePose has and some it has not (odd sizes, 7x7, 5x3, strides 2 and 3; OpenCV 4.6 refuses asymmetric
// pads, which the converter makes Pad layers). The nets
// must hold our layer where it is meant to be used (else the comparison proves nothing) and OpenCV's elsewhere.
#include <gtest/gtest.h>

#include <opencv2/dnn.hpp>

#include "pose/depthwise_conv.hpp"

namespace gpilot {
namespace {

struct ConvCase {
  int channels, h, w, k_h, k_w, stride_h, stride_w, pad_t, pad_l, pad_b, pad_r;
  bool bias = true, relu6 = false;
  int in_per_group = 1;  //!< 1: depthwise
};

std::string describe(const ConvCase& c) {
  return std::to_string(c.channels) + "x" + std::to_string(c.h) + "x" + std::to_string(c.w) + " k" + std::to_string(c.k_h) + "x" +
         std::to_string(c.k_w) + " s" + std::to_string(c.stride_h) + "," + std::to_string(c.stride_w) + " pads " +
         std::to_string(c.pad_t) + "," + std::to_string(c.pad_l) + "," + std::to_string(c.pad_b) + "," + std::to_string(c.pad_r) +
         (c.bias ? " bias" : "") + (c.relu6 ? " relu6" : "");
}

// The net of one convolution (and a ReLU6), made in or out of our scope; returns its output and the conv
// layer's type.
cv::Mat run(const ConvCase& c, const cv::Mat& image, const cv::Mat& weights, const cv::Mat& bias, bool ours, std::string& type) {
  const DepthwiseConvScope scope(ours);
  cv::dnn::LayerParams lp;
  lp.name = "conv";
  lp.type = "Convolution";
  lp.set("kernel_h", c.k_h);
  lp.set("kernel_w", c.k_w);
  lp.set("stride_h", c.stride_h);
  lp.set("stride_w", c.stride_w);
  lp.set("pad_t", c.pad_t);
  lp.set("pad_l", c.pad_l);
  lp.set("pad_b", c.pad_b);
  lp.set("pad_r", c.pad_r);
  lp.set("num_output", c.channels);
  lp.set("group", c.channels / c.in_per_group);
  lp.set("bias_term", c.bias);
  lp.blobs.push_back(weights);
  if (c.bias) lp.blobs.push_back(bias);
  cv::dnn::Net net;
  net.addLayerToPrev(lp.name, lp.type, lp);
  if (c.relu6) {
    cv::dnn::LayerParams relu;
    relu.name = "relu6";
    relu.type = "ReLU6";
    relu.set("min_value", 0.0f);
    relu.set("max_value", 6.0f);
    net.addLayerToPrev(relu.name, relu.type, relu);
  }
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  net.setInput(image);
  const cv::Mat out = net.forward().clone();
  type = net.getLayer(net.getLayerId("conv"))->type;
  // The layer made in the scope stays: a second forward, out of it, gives the same.
  EXPECT_EQ(cv::norm(out, net.forward(), cv::NORM_INF), 0.0) << describe(c);
  return out;
}

// Both nets on one random image and random weights; max |ours - OpenCV's| relative to the output's range.
double compare(const ConvCase& c, std::string& type_ours, std::string& type_own) {
  cv::RNG rng(static_cast<uint64_t>(c.channels * 131 + c.h * 17 + c.k_w));
  cv::Mat image(std::vector<int>{1, c.channels, c.h, c.w}, CV_32F);
  cv::Mat weights(std::vector<int>{c.channels, c.in_per_group, c.k_h, c.k_w}, CV_32F);
  cv::Mat bias(std::vector<int>{c.channels}, CV_32F);
  rng.fill(image, cv::RNG::UNIFORM, -3.0, 3.0);
  rng.fill(weights, cv::RNG::UNIFORM, -1.0, 1.0);
  rng.fill(bias, cv::RNG::UNIFORM, -1.0, 1.0);
  const cv::Mat ours = run(c, image, weights, bias, true, type_ours);
  const cv::Mat own = run(c, image, weights, bias, false, type_own);
  EXPECT_EQ(ours.size, own.size) << describe(c);
  if (ours.size != own.size) return 1e9;
  double lo = 0, hi = 0;
  cv::minMaxIdx(own, &lo, &hi);
  EXPECT_GT(hi - lo, 1.0) << describe(c) << ": the output is flat, the comparison proves little";
  return cv::norm(ours, own, cv::NORM_INF) / std::max(1.0, hi - lo);
}

TEST(DepthwiseConv, MatchesOpenCVsOwnOnEveryShape) {
  const std::vector<ConvCase> cases = {
      {24, 64, 64, 5, 5, 1, 1, 2, 2, 2, 2},                 // BlazePose: stride 1, same pads
      {48, 33, 31, 5, 5, 2, 2, 0, 0, 0, 0},                 // stride 2 after a Pad layer, odd sizes
      {48, 32, 32, 5, 5, 2, 2, 2, 2, 2, 2},                 // stride 2 with pads (OpenCV 4.6: symmetric only)
      {16, 7, 7, 5, 5, 1, 1, 2, 2, 2, 2, false, true},      // small plane, no bias, ReLU6 fused
      {8, 20, 13, 7, 7, 1, 1, 3, 3, 3, 3, true, true},      // 7x7
      {8, 19, 23, 5, 3, 1, 2, 2, 1, 2, 1},                  // 5x3, strides differ
      {5, 26, 26, 5, 5, 3, 3, 2, 2, 2, 2},                  // stride 3
      {4, 3, 4, 5, 5, 1, 1, 2, 2, 2, 2},                    // image smaller than the kernel
  };
  for (const ConvCase& c : cases) {
    std::string ours, own;
    const double diff = compare(c, ours, own);
    EXPECT_LT(diff, 1e-5) << describe(c);
    EXPECT_EQ(ours, kDepthwiseConvLayerType) << describe(c) << ": ours was not used";
    EXPECT_EQ(own, "Convolution") << describe(c);
  }
}

TEST(DepthwiseConv, LeavesTo3x3AndToOrdinaryConvolutionsOpenCVsOwn) {
  for (const ConvCase& c : {ConvCase{16, 32, 32, 3, 3, 1, 1, 1, 1, 1, 1},                           // vectorised by OpenCV
                            ConvCase{16, 32, 32, 5, 5, 1, 1, 2, 2, 2, 2, true, false, 4}}) {  // 4 channels a group
    std::string ours, own;
    EXPECT_LT(compare(c, ours, own), 1e-5) << describe(c);
    EXPECT_EQ(ours, "Convolution") << describe(c);
  }
}

TEST(DepthwiseConv, KernelAloneGivesTheSumOfTheTapsInsideTheImage) {
  // A 3x4 image of one channel, a 5x5 kernel of ones with pads 2: each output is the sum of the pixels within
  // two of it (the known answer, by hand), plus the bias.
  const float image[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  std::vector<float> ones(25, 1.0f), out(12);
  const float bias = 0.5f;
  DepthwiseConvShape s;
  s.channels = 1, s.in_h = 3, s.in_w = 4, s.out_h = 3, s.out_w = 4, s.k_h = 5, s.k_w = 5, s.pad_top = 2, s.pad_left = 2;
  depthwise_conv2d(s, image, ones.data(), &bias, out.data(), 0, 1);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      float want = bias;
      for (int v = 0; v < 3; ++v)
        for (int u = 0; u < 4; ++u)
          if (std::abs(v - y) <= 2 && std::abs(u - x) <= 2) want += image[v * 4 + u];
      EXPECT_FLOAT_EQ(out[static_cast<size_t>(y * 4 + x)], want) << y << "," << x;
    }
  EXPECT_FLOAT_EQ(out[0], 0.5f + 1 + 2 + 3 + 5 + 6 + 7 + 9 + 10 + 11);
}

// An image smaller than the kernel, without pads, has no output: a cv::Exception when the net is set up, as
// OpenCV's own layers refuse a shape (PoseModels turns it into a PoseModelError naming the file); the kernel
// alone writes nothing.
TEST(DepthwiseConv, AnImageSmallerThanTheKernelIsAnErrorNotACrash) {
  const ConvCase c{4, 3, 3, 5, 5, 1, 1, 0, 0, 0, 0};
  cv::Mat image(std::vector<int>{1, c.channels, c.h, c.w}, CV_32F, cv::Scalar(1));
  cv::Mat weights(std::vector<int>{c.channels, 1, c.k_h, c.k_w}, CV_32F, cv::Scalar(1));
  cv::Mat bias(std::vector<int>{c.channels}, CV_32F, cv::Scalar(0));
  std::string type;
  EXPECT_THROW(run(c, image, weights, bias, true, type), cv::Exception);
  DepthwiseConvShape s;
  s.channels = 1, s.in_h = 3, s.in_w = 3, s.out_h = -1, s.out_w = -1, s.k_h = 5, s.k_w = 5;
  float out = 7.0f;
  depthwise_conv2d(s, image.ptr<float>(), weights.ptr<float>(), nullptr, &out, 0, 1);
  EXPECT_EQ(out, 7.0f);
}

}  // namespace
}  // namespace gpilot
