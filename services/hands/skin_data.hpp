// Labelled skin data for training and scoring skin models: the UCI layout (one pixel a line: B G R label,
// 1 = skin, 2 = not) and image folders paired with mask folders by file stem (mask 255 = skin, 0 = not,
// exactly 128 = ignore, any other value skin when > 128). Plus the per-level counts a score is made from.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "skin_model.hpp"

namespace gpilot {

struct LabelledPixel {
  uint8_t b, g, r;
  bool skin;
};

// Throws SkinModelError naming the line of the first malformed row.
std::vector<LabelledPixel> read_uci_pixels(const std::string& path);

struct ImageMaskPair {
  std::string stem, image, mask;
};
// Every image in images_dir with a mask of the same stem in masks_dir, sorted by stem. Throws if none pair up.
std::vector<ImageMaskPair> pair_images_and_masks(const std::string& images_dir, const std::string& masks_dir);
// Reads one pair: bgr CV_8UC3, mask CV_8UC1 of the same size. Throws SkinModelError with the reason.
void read_pair(const ImageMaskPair& pair, cv::Mat& bgr, cv::Mat& mask);

enum class MaskLabel { NotSkin, Skin, Ignore };
inline MaskLabel mask_label(uint8_t v) {
  if (v == 128) return MaskLabel::Ignore;
  return v > 128 ? MaskLabel::Skin : MaskLabel::NotSkin;
}

// How many skin and non-skin pixels fell on each P(skin) level (0..255) of a model: enough for the
// score at any threshold and the whole ROC curve.
class LevelCounts {
 public:
  void add(uint8_t level, bool skin) { (skin ? skin_ : non_)[level] += 1; }
  void add_pixels(const SkinModel& model, const std::vector<LabelledPixel>& pixels);
  void add_image(const SkinModel& model, const cv::Mat& bgr, const cv::Mat& mask);

  struct Score {
    double threshold = 0, precision = 0, recall = 0, f1 = 0, false_positive_rate = 0;
    int64_t tp = 0, fp = 0, fn = 0, tn = 0;
  };
  // Skin iff level > SkinModel::threshold_level(threshold), exactly as SkinClassifier decides.
  Score score(double threshold) const;
  // One point per distinct level threshold, from everything-skin to nothing-skin.
  std::vector<Score> roc() const;
  // Area under the ROC curve (trapezoids).
  double auc() const;
  int64_t skin_total() const;
  int64_t non_skin_total() const;

 private:
  Score score_at_level(int level) const;
  std::array<int64_t, 256> skin_{}, non_{};
};

}  // namespace gpilot
