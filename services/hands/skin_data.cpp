#include "skin_data.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

namespace gpilot {

std::vector<LabelledPixel> read_uci_pixels(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw SkinModelError("cannot read pixel file " + path);
  std::vector<LabelledPixel> out;
  std::string line;
  int64_t n = 0;
  while (std::getline(f, line)) {
    ++n;
    if (line.empty() || line == "\r") continue;
    std::istringstream s(line);
    int b, g, r, label;
    std::string rest;
    if (!(s >> b >> g >> r >> label) || (s >> rest) || b < 0 || b > 255 || g < 0 || g > 255 || r < 0 || r > 255 ||
        (label != 1 && label != 2))
      throw SkinModelError(path + ":" + std::to_string(n) + ": expected 'B G R label' with 0..255 and label 1 (skin) or 2 (not)");
    out.push_back({static_cast<uint8_t>(b), static_cast<uint8_t>(g), static_cast<uint8_t>(r), label == 1});
  }
  if (out.empty()) throw SkinModelError(path + ": no pixels");
  return out;
}

std::vector<ImageMaskPair> pair_images_and_masks(const std::string& images_dir, const std::string& masks_dir) {
  namespace fs = std::filesystem;
  for (const auto& d : {images_dir, masks_dir})
    if (!fs::is_directory(d)) throw SkinModelError("not a folder: " + d);
  std::map<std::string, std::string> masks;
  for (const auto& e : fs::directory_iterator(masks_dir))
    if (e.is_regular_file()) masks[e.path().stem().string()] = e.path().string();
  std::vector<ImageMaskPair> out;
  for (const auto& e : fs::directory_iterator(images_dir)) {
    if (!e.is_regular_file()) continue;
    const auto it = masks.find(e.path().stem().string());
    if (it != masks.end()) out.push_back({it->first, e.path().string(), it->second});
  }
  if (out.empty()) throw SkinModelError("no image in " + images_dir + " has a mask of the same name in " + masks_dir);
  std::sort(out.begin(), out.end(), [](const ImageMaskPair& a, const ImageMaskPair& b) { return a.stem < b.stem; });
  return out;
}

void read_pair(const ImageMaskPair& pair, cv::Mat& bgr, cv::Mat& mask) {
  bgr = cv::imread(pair.image, cv::IMREAD_COLOR);
  mask = cv::imread(pair.mask, cv::IMREAD_GRAYSCALE);
  if (bgr.empty()) throw SkinModelError("cannot decode image " + pair.image);
  if (mask.empty()) throw SkinModelError("cannot decode mask " + pair.mask);
  if (bgr.size() != mask.size())
    throw SkinModelError("mask " + pair.mask + " is not the size of image " + pair.image);
}

void LevelCounts::add_pixels(const SkinModel& model, const std::vector<LabelledPixel>& pixels) {
  for (const auto& p : pixels) add(model.level(p.b, p.g, p.r), p.skin);
}

void LevelCounts::add_image(const SkinModel& model, const cv::Mat& bgr, const cv::Mat& mask) {
  CV_Assert(bgr.type() == CV_8UC3 && mask.type() == CV_8UC1 && bgr.size() == mask.size());
  for (int y = 0; y < bgr.rows; ++y) {
    const uint8_t* p = bgr.ptr<uint8_t>(y);
    const uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = 0; x < bgr.cols; ++x, p += 3) {
      const MaskLabel label = mask_label(m[x]);
      if (label != MaskLabel::Ignore) add(model.level(p[0], p[1], p[2]), label == MaskLabel::Skin);
    }
  }
}

int64_t LevelCounts::skin_total() const {
  int64_t n = 0;
  for (auto c : skin_) n += c;
  return n;
}

int64_t LevelCounts::non_skin_total() const {
  int64_t n = 0;
  for (auto c : non_) n += c;
  return n;
}

LevelCounts::Score LevelCounts::score_at_level(int level) const {
  Score s;
  for (int l = 0; l < 256; ++l) {
    const size_t i = static_cast<size_t>(l);
    if (l > level) {
      s.tp += skin_[i];
      s.fp += non_[i];
    } else {
      s.fn += skin_[i];
      s.tn += non_[i];
    }
  }
  s.threshold = (level + 1) / 255.0 - 1e-9;
  s.precision = s.tp + s.fp > 0 ? static_cast<double>(s.tp) / static_cast<double>(s.tp + s.fp) : 1.0;
  s.recall = s.tp + s.fn > 0 ? static_cast<double>(s.tp) / static_cast<double>(s.tp + s.fn) : 0.0;
  s.f1 = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0.0;
  s.false_positive_rate = s.fp + s.tn > 0 ? static_cast<double>(s.fp) / static_cast<double>(s.fp + s.tn) : 0.0;
  return s;
}

LevelCounts::Score LevelCounts::score(double threshold) const {
  Score s = score_at_level(SkinModel::threshold_level(threshold));
  s.threshold = threshold;
  return s;
}

std::vector<LevelCounts::Score> LevelCounts::roc() const {
  std::vector<Score> out;
  for (int level = -1; level < 256; ++level) out.push_back(score_at_level(level));
  return out;
}

double LevelCounts::auc() const {
  const auto pts = roc();
  double area = 0;
  for (size_t i = 1; i < pts.size(); ++i)
    area += (pts[i - 1].false_positive_rate - pts[i].false_positive_rate) * (pts[i - 1].recall + pts[i].recall) / 2;
  return area;
}

}  // namespace gpilot
