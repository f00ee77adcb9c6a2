#include "skin_adapter.hpp"

#include <algorithm>
#include <cmath>

namespace gpilot {

SkinAdapter::SkinAdapter(const SkinParams& params, const SkinModel& prior)
    : p_(params), prior_(prior), prior_classifier_(prior, params.threshold), adapted_(prior_classifier_) {
  if (p_.adapt.enabled && !prior.has_likelihoods())
    throw SkinModelError("hands.skin.adapt needs a skin model with likelihood tables: retrain it with gpilot-skin-train "
                         "(data/skin/README.md), or set hands.skin.adapt.enabled=false");
}

void SkinAdapter::reset() {
  user_.clear();
  scene_.clear();
  user_smooth_.clear();
  user_colour_.clear();
  user_samples_ = scene_samples_ = clothing_samples_seen_ = 0;
  frames_since_rebuild_ = 0;
  dirty_ = built_ = false;
  adapted_ = prior_classifier_;
  changed_fraction_ = 0;
}

void SkinAdapter::learn_user(const cv::Mat& bgr, const cv::Rect2f& face) {
  if (!p_.adapt.enabled) return;
  CV_Assert(bgr.type() == CV_8UC3);
  const auto& a = p_.adapt;
  const cv::Rect band = cv::Rect(cv::Point(static_cast<int>(std::lround(face.x + a.face_band_side * face.width)),
                                           static_cast<int>(std::lround(face.y + a.face_band_top * face.height))),
                                 cv::Point(static_cast<int>(std::lround(face.x + (1 - a.face_band_side) * face.width)),
                                           static_cast<int>(std::lround(face.y + a.face_band_bottom * face.height)))) &
                        cv::Rect(0, 0, bgr.cols, bgr.rows);
  if (band.empty()) return;
  const int min_level = SkinModel::threshold_level(a.face_min_prior);
  sample_.assign(prior_.table().size(), 0.0);
  double n = 0;
  for (int y = band.y; y < band.br().y; ++y) {
    const uint8_t* px = bgr.ptr<uint8_t>(y) + 3 * band.x;
    for (int x = 0; x < band.width; ++x, px += 3) {
      if (prior_.level(px[0], px[1], px[2]) <= min_level) continue;  // eyes, brows, hair, background
      sample_[static_cast<size_t>(prior_.bin(px[0], px[1], px[2]))] += 1;
      n += 1;
    }
  }
  if (n < a.min_face_samples) return;  // too small or not a face: nothing learnt
  blend_histogram(user_, sample_, n, a.user_rate, user_samples_ == 0);
  user_samples_ += static_cast<int64_t>(n);
  // Smoothed once per face (about once a second), not at every rebuild.
  user_smooth_ = smooth_histogram(user_, prior_.bins(), a.smoothing_sigma);
  if (a.clothing_weight > 0) {
    const double level = a.clothing_user_level * *std::max_element(user_smooth_.begin(), user_smooth_.end());
    user_colour_.assign(user_smooth_.size(), 0);
    for (size_t i = 0; i < user_smooth_.size(); ++i) user_colour_[i] = user_smooth_[i] > level ? 1 : 0;
  }
  dirty_ = true;
}

double SkinAdapter::sample_outside(const cv::Mat& bgr, const cv::Rect& exclude) {
  CV_Assert(bgr.type() == CV_8UC3);
  const int stride = p_.adapt.scene_stride;
  sample_.assign(prior_.table().size(), 0.0);
  double n = 0;
  for (int y = stride / 2; y < bgr.rows; y += stride) {
    const uint8_t* row = bgr.ptr<uint8_t>(y);
    const bool row_in = y >= exclude.y && y < exclude.br().y;
    for (int x = stride / 2; x < bgr.cols; x += stride) {
      if (row_in && x >= exclude.x && x < exclude.br().x) continue;
      const uint8_t* px = row + 3 * x;
      sample_[static_cast<size_t>(prior_.bin(px[0], px[1], px[2]))] += 1;
      n += 1;
    }
  }
  return n;
}

void SkinAdapter::learn_scene(const cv::Mat& bgr, const cv::Rect& exclude) {
  if (!p_.adapt.enabled || p_.adapt.scene_weight <= 0) return;
  const double n = sample_outside(bgr, exclude);
  if (n < p_.adapt.min_scene_samples) return;
  blend_histogram(scene_, sample_, n, p_.adapt.scene_rate, scene_samples_ == 0);
  scene_samples_ += static_cast<int64_t>(n);
  dirty_ = true;
}

const SkinClassifier& SkinAdapter::classifier_for_frame(const ClothingColours* clothing) {
  const int64_t clothing_samples = clothing ? clothing->samples() : 0;
  if (clothing_samples != clothing_samples_seen_) dirty_ = true;
  clothing_samples_seen_ = clothing_samples;
  ++frames_since_rebuild_;
  if (dirty_ && (!built_ || frames_since_rebuild_ >= p_.adapt.rebuild_frames)) rebuild(clothing);
  return adapted_;
}

void SkinAdapter::rebuild(const ClothingColours* clothing) {
  frames_since_rebuild_ = 0;
  dirty_ = false;
  const auto& a = p_.adapt;
  const int bins = prior_.bins();
  const std::vector<double>& user = user_smooth_;
  const std::vector<double> scene = scene_.empty() ? scene_ : smooth_histogram(scene_, bins, a.smoothing_sigma);
  const std::vector<double> clothing_smooth = !clothing || clothing->histogram().empty()
                                                  ? std::vector<double>()
                                                  : smooth_histogram(clothing->histogram(), bins, a.smoothing_sigma);
  const double wu = user.empty() ? 0.0 : a.user_weight, ws = scene.empty() ? 0.0 : a.scene_weight;
  const double wc = clothing_smooth.empty() ? 0.0 : a.clothing_weight;
  const double ps = prior_.skin_prior(), pn = 1.0 - ps, t = p_.threshold;
  const auto& ls = prior_.skin_likelihood();
  const auto& ln = prior_.non_likelihood();
  const auto& table = prior_classifier_.mask_table();
  std::vector<uint8_t> mask(ls.size());
  size_t changed = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    const double s = wu > 0 ? a.table_share * ls[i] + wu * user[i] : ls[i];
    const double o = (1 - ws - wc) * ln[i] + (ws > 0 ? ws * scene[i] : 0.0) + (wc > 0 ? wc * clothing_smooth[i] : 0.0);
    const double total = s * ps + o * pn;
    mask[i] = total > 0 && s * ps > t * total ? 1 : 0;
    changed += mask[i] != table[i];
  }
  changed_fraction_ = static_cast<double>(changed) / static_cast<double>(mask.size());
  built_ = true;
  adapted_ = SkinClassifier(bins, std::move(mask));
}

}  // namespace gpilot
