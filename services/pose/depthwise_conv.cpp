// Each channel's plane is first copied into a zero-bordered plane (its pads around it), split by the strides
// into phases (phase (py, px) holds the rows py, py + stride_h, ... and of them the columns px, px + stride_w,
// ...). In a phase, tap (ky, kx) of output (oy, ox) is at row oy + ky / stride_h, column ox + kx / stride_w: a
// fixed offset from (oy, ox). So over a grid of the phases' width, each tap adds its product to every output in
// one pass over consecutive floats (eight at a time, no bounds tests), and the outputs are then copied out of
// the grid.
#include "depthwise_conv.hpp"

#include <algorithm>
#include <cfloat>
#include <mutex>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/all_layers.hpp>

namespace gpilot {
namespace {

// Eight floats in vector registers (GCC's vector extension: two SSE registers, or one AVX register in the AVX2
// build below).
typedef float Floats8 __attribute__((vector_size(32)));

// o[x] += the sum over a kernel row's taps t < k of w[t] * r[t][x], for x in [0, n), eight at a time. K: k known
// when compiled (0: not), so that the taps unroll.
template <int K>
inline __attribute__((always_inline)) void row_taps(float* o, const float* const* r, const float* w, int k, int n) {
  if (K) k = K;
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    Floats8 acc, in;
    __builtin_memcpy(&acc, o + x, sizeof acc);
    for (int t = 0; t < k; ++t) {
      __builtin_memcpy(&in, r[t] + x, sizeof in);
      acc += w[t] * in;
    }
    __builtin_memcpy(o + x, &acc, sizeof acc);
  }
  for (; x < n; ++x) {
    float acc = o[x];
    for (int t = 0; t < k; ++t) acc += w[t] * r[t][x];
    o[x] = acc;
  }
}

inline __attribute__((always_inline)) void convolve(const DepthwiseConvShape& s, const float* in, const float* weights,
                                                    const float* bias, float* out, int channel_begin, int channel_end) {
  if (s.out_h <= 0 || s.out_w <= 0 || s.stride_h <= 0 || s.stride_w <= 0) return;  // no output
  const int sh = s.stride_h, sw = s.stride_w;
  // The bordered plane: tall and wide enough for every tap of every output; its phases, each phase_h x phase_w.
  const int bordered_h = std::max(s.in_h + s.pad_top, (s.out_h - 1) * sh + s.k_h);
  const int bordered_w = std::max(s.in_w + s.pad_left, (s.out_w - 1) * sw + s.k_w);
  const int phase_h = (bordered_h + sh - 1) / sh, phase_w = (bordered_w + sw - 1) / sw;
  const size_t phase_plane = static_cast<size_t>(phase_h) * phase_w;
  std::vector<float> phases(phase_plane * sh * sw, 0.0f);
  const auto phase_of = [&](int y, int x) { return phases.data() + static_cast<size_t>(y % sh * sw + x % sw) * phase_plane; };
  // Bordered column x = image column x - pad_left; the first image column of phase px and how many it holds.
  std::vector<int> first(static_cast<size_t>(sw)), count(first.size());
  for (int px = 0; px < sw; ++px) {
    int x = px;
    while (x < s.pad_left) x += sw;
    first[px] = x - s.pad_left;
    count[px] = first[px] < s.in_w ? (s.in_w - first[px] + sw - 1) / sw : 0;
  }
  // Tap (ky, kx) of grid element i = oy * phase_w + ox: its phase's element i + offset.
  std::vector<const float*> taps(static_cast<size_t>(s.k_h) * s.k_w);
  for (int ky = 0; ky < s.k_h; ++ky)
    for (int kx = 0; kx < s.k_w; ++kx)
      taps[static_cast<size_t>(ky) * s.k_w + kx] = phase_of(ky, kx) + static_cast<size_t>(ky / sh) * phase_w + kx / sw;
  const int n = (s.out_h - 1) * phase_w + s.out_w;
  std::vector<float> grid(static_cast<size_t>(n));
  const size_t in_plane = static_cast<size_t>(s.in_h) * s.in_w, out_plane = static_cast<size_t>(s.out_h) * s.out_w;
  for (int c = channel_begin; c < channel_end; ++c) {
    // The border stays zero: every channel writes the same places.
    const float* src = in + c * in_plane;
    for (int y = 0; y < s.in_h; ++y)
      for (int px = 0; px < sw; ++px) {
        const int by = y + s.pad_top, bx = first[px] + s.pad_left;
        const float* from = src + static_cast<size_t>(y) * s.in_w + first[px];
        float* to = phase_of(by, bx) + static_cast<size_t>(by / sh) * phase_w + bx / sw;
        if (sw == 1)
          std::copy(from, from + count[px], to);
        else
          for (int j = 0; j < count[px]; ++j) to[j] = from[j * sw];
      }
    const float* w = weights + static_cast<size_t>(c) * taps.size();
    std::fill(grid.begin(), grid.end(), bias ? bias[c] : 0.0f);
    for (int ky = 0; ky < s.k_h; ++ky) {
      const float* const* row = taps.data() + static_cast<size_t>(ky) * s.k_w;
      if (s.k_w == 5)
        row_taps<5>(grid.data(), row, w + ky * s.k_w, 5, n);
      else
        row_taps<0>(grid.data(), row, w + ky * s.k_w, s.k_w, n);
    }
    float* dst = out + c * out_plane;
    for (int oy = 0; oy < s.out_h; ++oy)
      std::copy(grid.data() + static_cast<size_t>(oy) * phase_w, grid.data() + static_cast<size_t>(oy) * phase_w + s.out_w,
                dst + static_cast<size_t>(oy) * s.out_w);
  }
}

__attribute__((target("avx2,fma"))) void convolve_avx2(const DepthwiseConvShape& s, const float* in, const float* weights,
                                                       const float* bias, float* out, int channel_begin, int channel_end) {
  convolve(s, in, weights, bias, out, channel_begin, channel_end);
}

void convolve_baseline(const DepthwiseConvShape& s, const float* in, const float* weights, const float* bias, float* out,
                       int channel_begin, int channel_end) {
  convolve(s, in, weights, bias, out, channel_begin, channel_end);
}

}  // namespace

void depthwise_conv2d(const DepthwiseConvShape& s, const float* in, const float* weights, const float* bias, float* out,
                      int channel_begin, int channel_end) {
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  (avx2 ? convolve_avx2 : convolve_baseline)(s, in, weights, bias, out, channel_begin, channel_end);
}

namespace {

thread_local bool ours_enabled = false;

// A depthwise convolution layer of cv::dnn's OpenCV backend, with a ReLU / ReLU6 fused (min, max clamp).
class DepthwiseConvLayer : public cv::dnn::Layer {
 public:
  DepthwiseConvLayer(const cv::dnn::LayerParams& params, const cv::dnn::BaseConvolutionLayer& parsed) : Layer(params) {
    type = kDepthwiseConvLayerType;
    k_h_ = static_cast<int>(parsed.kernel_size[0]);
    k_w_ = static_cast<int>(parsed.kernel_size[1]);
    stride_h_ = static_cast<int>(parsed.strides[0]);
    stride_w_ = static_cast<int>(parsed.strides[1]);
    pad_top_ = static_cast<int>(parsed.pads_begin[0]);
    pad_left_ = static_cast<int>(parsed.pads_begin[1]);
    pad_bottom_ = static_cast<int>(parsed.pads_end[0]);
    pad_right_ = static_cast<int>(parsed.pads_end[1]);
    weights_ = blobs[0].isContinuous() ? blobs[0] : blobs[0].clone();
    if (blobs.size() > 1) bias_ = blobs[1].reshape(1, 1).clone();
  }

  bool getMemoryShapes(const std::vector<cv::dnn::MatShape>& inputs, const int, std::vector<cv::dnn::MatShape>& outputs,
                       std::vector<cv::dnn::MatShape>&) const override {
    CV_Assert(inputs.size() == 1 && inputs[0].size() == 4 && inputs[0][1] == weights_.size[0]);
    const cv::dnn::MatShape& in = inputs[0];
    const int out_h = (in[2] + pad_top_ + pad_bottom_ - k_h_) / stride_h_ + 1;
    const int out_w = (in[3] + pad_left_ + pad_right_ - k_w_) / stride_w_ + 1;
    CV_Assert(in[2] + pad_top_ + pad_bottom_ >= k_h_ && in[3] + pad_left_ + pad_right_ >= k_w_ && out_h > 0 && out_w > 0);
    outputs.assign(1, cv::dnn::MatShape{in[0], in[1], out_h, out_w});
    return false;
  }

  bool setActivation(const cv::Ptr<cv::dnn::ActivationLayer>& layer) override {
    if (layer.empty()) {
      min_ = -FLT_MAX, max_ = FLT_MAX;
      return false;
    }
    if (const auto* relu6 = dynamic_cast<const cv::dnn::ReLU6Layer*>(layer.get())) {
      min_ = relu6->minValue, max_ = relu6->maxValue;
      return true;
    }
    if (const auto* relu = dynamic_cast<const cv::dnn::ReLULayer*>(layer.get()); relu && relu->negativeSlope == 0.0f) {
      min_ = 0.0f, max_ = FLT_MAX;
      return true;
    }
    return false;
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr, cv::OutputArrayOfArrays) override {
    std::vector<cv::Mat> inputs, outputs;
    inputs_arr.getMatVector(inputs);
    outputs_arr.getMatVector(outputs);
    CV_Assert(inputs.size() == 1 && outputs.size() == 1 && inputs[0].type() == CV_32F && outputs[0].type() == CV_32F);
    const cv::Mat& in = inputs[0];
    cv::Mat& out = outputs[0];
    DepthwiseConvShape s;
    s.channels = in.size[1], s.in_h = in.size[2], s.in_w = in.size[3], s.out_h = out.size[2], s.out_w = out.size[3];
    s.k_h = k_h_, s.k_w = k_w_, s.stride_h = stride_h_, s.stride_w = stride_w_, s.pad_top = pad_top_, s.pad_left = pad_left_;
    const size_t in_image = static_cast<size_t>(s.channels) * s.in_h * s.in_w;
    const size_t out_image = static_cast<size_t>(s.channels) * s.out_h * s.out_w, out_plane = out_image / s.channels;
    const float* bias = bias_.empty() ? nullptr : bias_.ptr<float>();
    for (int n = 0; n < in.size[0]; ++n) {
      const float* src = in.ptr<float>() + n * in_image;
      float* dst = out.ptr<float>() + n * out_image;
      cv::parallel_for_(cv::Range(0, s.channels), [&](const cv::Range& r) {
        depthwise_conv2d(s, src, weights_.ptr<float>(), bias, dst, r.start, r.end);
        if (min_ != -FLT_MAX || max_ != FLT_MAX)
          for (float *p = dst + r.start * out_plane, *e = dst + r.end * out_plane; p < e; ++p) *p = std::min(std::max(*p, min_), max_);
      });
    }
  }

 private:
  int k_h_ = 0, k_w_ = 0, stride_h_ = 1, stride_w_ = 1, pad_top_ = 0, pad_left_ = 0, pad_bottom_ = 0, pad_right_ = 0;
  cv::Mat weights_, bias_;
  float min_ = -FLT_MAX, max_ = FLT_MAX;
};

// cv::dnn's constructor for every Convolution layer once ours is registered: ours for the depthwise convolutions
// it runs unvectorised, OpenCV's own (made as OpenCV makes it) for the rest.
cv::Ptr<cv::dnn::Layer> make_convolution(cv::dnn::LayerParams& params) {
  cv::Ptr<cv::dnn::BaseConvolutionLayer> own = cv::dnn::ConvolutionLayer::create(params);
  if (!ours_enabled || params.blobs.empty()) return own;
  const cv::Mat& w = params.blobs[0];
  const bool depthwise = w.dims == 4 && w.type() == CV_32F && w.size[1] == 1 && params.get<int>("group", 1) == w.size[0] &&
                         own->numOutput == w.size[0];
  const bool plain = own->kernel_size.size() == 2 && own->padMode.empty() && own->pads_begin.size() == 2 &&
                     own->pads_end.size() == 2 && own->strides.size() == 2 && own->dilations.size() == 2 &&
                     own->dilations[0] == 1 && own->dilations[1] == 1;
  const bool vectorised_by_opencv = plain && own->kernel_size[0] == 3 && own->kernel_size[1] == 3;
  const bool bias_fits = params.blobs.size() < 2 || params.blobs[1].total() == static_cast<size_t>(w.size[0]);
  if (!depthwise || !plain || vectorised_by_opencv || !bias_fits) return own;
  return cv::makePtr<DepthwiseConvLayer>(params, *own);
}

}  // namespace

DepthwiseConvScope::DepthwiseConvScope(bool enabled) : previous_(ours_enabled) {
  static std::once_flag registered;
  std::call_once(registered, [] { cv::dnn::LayerFactory::registerLayer("Convolution", make_convolution); });
  ours_enabled = enabled;
}

DepthwiseConvScope::~DepthwiseConvScope() { ours_enabled = previous_; }

}  // namespace gpilot
