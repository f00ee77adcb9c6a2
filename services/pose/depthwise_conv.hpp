// A depthwise 2-D convolution for cv::dnn. OpenCV 4.6 vectorises depthwise convolutions only when they are 3x3
// (fast_convolution/depthwise_convolution.cpp); BlazePose's nets are mostly 5x5 depthwise, which it runs one
// multiply at a time: 12 of the lite landmark model's 18 ms, 1.6 ms on this kernel.
//
//   {
//     DepthwiseConvScope ours;               // nets set up in this scope run their depthwise non-3x3 convs here
//     net = cv::dnn::readNetFromONNX(path);
//     net.forward(...);                      // cv::dnn makes its layers at the first forward
//   }
#pragma once

namespace gpilot {

// One image's depthwise convolution, NCHW with N = 1: out[c] = bias[c] + sum over the k_h x k_w taps of
// weights[c] and in[c] (zero outside the image), output of out_h x out_w. bias may be null.
struct DepthwiseConvShape {
  int channels = 0, in_h = 0, in_w = 0, out_h = 0, out_w = 0;
  int k_h = 0, k_w = 0, stride_h = 1, stride_w = 1, pad_top = 0, pad_left = 0;
};
void depthwise_conv2d(const DepthwiseConvShape& s, const float* in, const float* weights, const float* bias, float* out,
                      int channel_begin, int channel_end);

// While one is alive on this thread, a cv::dnn Convolution layer made on it that is depthwise (one input channel
// a group), 2-D, undilated, with explicit pads and a kernel other than 3x3 is ours (a ReLU or ReLU6 after it is
// fused); every other convolution is OpenCV's own. Scopes nest.
class DepthwiseConvScope {
 public:
  explicit DepthwiseConvScope(bool enabled = true);
  ~DepthwiseConvScope();
  DepthwiseConvScope(const DepthwiseConvScope&) = delete;
  DepthwiseConvScope& operator=(const DepthwiseConvScope&) = delete;

 private:
  bool previous_;
};

// The type name our layers report (cv::dnn::Layer::type), for tests that count them.
constexpr const char* kDepthwiseConvLayerType = "gpilot.DepthwiseConvolution";

}  // namespace gpilot
