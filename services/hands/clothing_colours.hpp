// The user's clothing colours, learnt in one place: once a frame from the torso of the user box (torso_rect,
// hand_detector.hpp), for the skin method's two readers of them:
//   - the arm test (HandDetector, Alg. 1's arm_connected): a colour worn on this frame's torso joins a hand to
//     the body as a sleeve does. Every torso pixel counts, B, G, R in 16 levels each, this frame only: the arm
//     is looked for in this frame's pixels, and a colour is worn when at least 1 in 200 of them have it.
//   - the skin model (SkinAdapter): C(c), a share of P(colour|not skin), so that a shirt the table calls skin
//     is the shirt. Every adapt.scene_stride-th pixel in the skin table's bins, blended in at
//     adapt.clothing_rate (decay), and only once the user's skin colours are known (from a face) and without
//     them: a hand held in front of the body is the user's skin, not clothing.
// State depends only on the frames and torsos given; no clock.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "hands/hands_params.hpp"

namespace gpilot {

class ClothingColours {
 public:
  // model_bins: the skin table's bins per channel (a power of two, 2..256), which C(c) is kept in.
  // Throws SkinModelError for any other.
  ClothingColours(const SkinAdaptParams& adapt, int model_bins);

  // Learns this frame's torso (clipped to the image; empty: nothing worn). user_skin_colours: per skin-table bin,
  // one of the user's skin colours (SkinAdapter::user_skin_colours); empty: C(c) learns nothing from this frame.
  void learn(const cv::Mat& bgr, const cv::Rect& torso, const std::vector<uint8_t>& user_skin_colours = {});
  // Forgets everything (a new user).
  void reset();

  // Whether this colour (a BGR pixel) is worn on the torso of the last frame learnt.
  bool worn(const uint8_t* bgr) const { return frame_counts_[static_cast<size_t>(worn_bin(bgr))] >= worn_min_count_; }

  // C(c) over the skin table's bins, normalised and decayed; empty until something was learnt.
  const std::vector<double>& histogram() const { return histogram_; }
  // Pixels C(c) has learnt from in all.
  int64_t samples() const { return samples_; }

 private:
  static constexpr int kWornShift = 4;  // 16 levels a channel
  static int worn_bin(const uint8_t* bgr) {
    constexpr int levels = 256 >> kWornShift;
    return ((bgr[0] >> kWornShift) * levels + (bgr[1] >> kWornShift)) * levels + (bgr[2] >> kWornShift);
  }
  int model_bin(const uint8_t* bgr) const {
    return ((bgr[0] >> model_shift_) * model_bins_ + (bgr[1] >> model_shift_)) * model_bins_ + (bgr[2] >> model_shift_);
  }
  // Every stride-th pixel of the torso, the user's skin colours left out, into sample_; their number.
  double sample_torso(const cv::Mat& bgr, const cv::Rect& torso, const std::vector<uint8_t>& user_skin_colours);

  double rate_;
  int stride_;
  int model_bins_, model_shift_;
  std::vector<int64_t> frame_counts_;  //!< this frame's torso pixels per worn_bin
  int64_t worn_min_count_ = 1;
  std::vector<double> histogram_, sample_;
  int64_t samples_ = 0;
};

}  // namespace gpilot
