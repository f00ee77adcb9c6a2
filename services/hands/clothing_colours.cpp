#include "clothing_colours.hpp"

#include <algorithm>

#include "hands/skin_model.hpp"

namespace gpilot {

namespace {

// A colour is worn when at least 1 in this many of the torso's pixels have it (0.5 %): rarer colours there are
// its edges, shadows and what shows through, which an arm must not be joined by.
constexpr int64_t kWornColourOneIn = 200;

// The first of every stride-th coordinate from stride / 2 (the grid the scene is sampled on too) at or after v.
int first_on_grid(int v, int stride) {
  const int start = stride / 2;
  return v <= start ? start : start + (v - start + stride - 1) / stride * stride;
}

}  // namespace

ClothingColours::ClothingColours(const SkinAdaptParams& adapt, int model_bins)
    : rate_(adapt.clothing_rate), stride_(adapt.scene_stride), model_bins_(model_bins),
      model_shift_(8 - log2_exact(model_bins)), frame_counts_(size_t{1} << (3 * (8 - kWornShift)), 0) {
  if (log2_exact(model_bins) < 1) throw SkinModelError("bins per channel must be a power of two from 2 to 256");
}

void ClothingColours::reset() {
  std::fill(frame_counts_.begin(), frame_counts_.end(), 0);
  worn_min_count_ = 1;
  histogram_.clear();
  samples_ = 0;
}

void ClothingColours::learn(const cv::Mat& bgr, const cv::Rect& torso, const std::vector<uint8_t>& user_skin_colours) {
  CV_Assert(bgr.type() == CV_8UC3);
  const cv::Rect t = torso & cv::Rect(0, 0, bgr.cols, bgr.rows);
  std::fill(frame_counts_.begin(), frame_counts_.end(), 0);
  for (int y = t.y; y < t.br().y; ++y) {
    const uint8_t* px = bgr.ptr<uint8_t>(y) + 3 * t.x;
    for (int x = 0; x < t.width; ++x, px += 3) ++frame_counts_[static_cast<size_t>(worn_bin(px))];
  }
  worn_min_count_ = std::max<int64_t>(1, static_cast<int64_t>(t.area()) / kWornColourOneIn);
  // C(c) only once the user's skin is known from a face: without it a hand held in front of the body, a bare neck
  // or chest would be learnt as clothing and the user's hands stop being skin (real photos, annotation box: FRONT
  // found 5 -> 1 of 22, OUT 5 -> 3 of 12).
  if (user_skin_colours.empty()) return;
  CV_Assert(user_skin_colours.size() == static_cast<size_t>(model_bins_) * model_bins_ * model_bins_);
  const double n = sample_torso(bgr, t, user_skin_colours);
  if (n <= 0) return;
  blend_histogram(histogram_, sample_, n, rate_, samples_ == 0);
  samples_ += static_cast<int64_t>(n);
}

double ClothingColours::sample_torso(const cv::Mat& bgr, const cv::Rect& torso, const std::vector<uint8_t>& user_skin_colours) {
  sample_.assign(user_skin_colours.size(), 0.0);
  double n = 0;
  for (int y = first_on_grid(torso.y, stride_); y < torso.br().y; y += stride_) {
    const uint8_t* row = bgr.ptr<uint8_t>(y);
    for (int x = first_on_grid(torso.x, stride_); x < torso.br().x; x += stride_) {
      const auto bin = static_cast<size_t>(model_bin(row + 3 * x));
      if (user_skin_colours[bin]) continue;
      sample_[bin] += 1;
      n += 1;
    }
  }
  return n;
}

}  // namespace gpilot
