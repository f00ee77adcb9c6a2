#include "skin_model.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace gpilot {
namespace {

constexpr const char* kFormat = "gpilot-skin-histogram-1";

// The description is stored as a YAML literal block, which always reads back with one final newline.
std::string trim_end(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// One pass of a 1-D Gaussian along one axis of a bins^3 volume (zero outside), line by line. The learnt
// histograms are sparse (a scene, a shirt, a face fill a few hundred of 32768 bins): a line that is all zero
// stays zero, and is skipped (the smoothing was 15 % of the hands stage's CPU). Each output sums its taps in
// the same order whether or not lines are skipped, so the result is the same to the bit.
std::vector<double> blur_axis(const std::vector<double>& in, int bins, int axis, const std::vector<double>& kernel) {
  const int radius = static_cast<int>(kernel.size() / 2);
  const int stride = axis == 0 ? bins * bins : axis == 1 ? bins : 1;
  std::vector<double> out(in.size(), 0.0);
  const int lines = bins * bins;
  for (int line = 0; line < lines; ++line) {
    // The first index of this line: the axis' own digit is 0, the other two are the line's.
    const int low = line % stride, high = line / stride;
    const size_t base = static_cast<size_t>(high) * static_cast<size_t>(stride) * bins + static_cast<size_t>(low);
    bool any = false;
    for (int pos = 0; pos < bins && !any; ++pos) any = in[base + static_cast<size_t>(pos) * stride] != 0.0;
    if (!any) continue;
    for (int pos = 0; pos < bins; ++pos) {
      double acc = 0;
      for (int k = -radius; k <= radius; ++k) {
        const int q = pos + k;
        if (q < 0 || q >= bins) continue;
        acc += kernel[static_cast<size_t>(k + radius)] * in[base + static_cast<size_t>(q) * stride];
      }
      out[base + static_cast<size_t>(pos) * stride] = acc;
    }
  }
  return out;
}

}  // namespace

std::vector<double> smooth_histogram(std::vector<double> v, int bins, double sigma) {
  if (sigma <= 0) return v;
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> kernel(static_cast<size_t>(2 * radius + 1));
  double sum = 0;
  for (int k = -radius; k <= radius; ++k) sum += kernel[static_cast<size_t>(k + radius)] = std::exp(-0.5 * k * k / (sigma * sigma));
  for (auto& k : kernel) k /= sum;
  for (int axis = 0; axis < 3; ++axis) v = blur_axis(v, bins, axis, kernel);
  return v;
}

namespace {

// Likelihoods are stored as -log2(P) in 1/8 bit steps, one byte a bin: 255 stands for P <= 2^-31.9.
constexpr double kLogSteps = 8.0;

uint8_t encode_likelihood(double p) {
  if (p <= 0) return 255;
  return static_cast<uint8_t>(std::clamp(std::lround(-std::log2(p) * kLogSteps), 0L, 255L));
}

float decode_likelihood(uint8_t q) { return static_cast<float>(std::exp2(-q / kLogSteps)); }

std::string to_hex(const std::vector<uint8_t>& bytes) {
  static const char* hex = "0123456789abcdef";
  std::string text;
  for (size_t i = 0; i < bytes.size(); ++i) {
    text += hex[bytes[i] >> 4];
    text += hex[bytes[i] & 15];
    if ((i + 1) % 64 == 0) text += '\n';
  }
  return text;
}

std::vector<uint8_t> from_hex(const std::string& text, const std::string& what) {
  std::vector<uint8_t> out;
  out.reserve(text.size() / 2);
  int hi = -1;
  for (char c : text) {
    int d;
    if (c >= '0' && c <= '9') d = c - '0';
    else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    else if (c == '\n' || c == ' ' || c == '\r') continue;
    else throw SkinModelError(what + " has a character that is not a hex digit");
    if (hi < 0) {
      hi = d;
    } else {
      out.push_back(static_cast<uint8_t>(hi * 16 + d));
      hi = -1;
    }
  }
  if (hi >= 0) throw SkinModelError(what + " has an odd number of hex digits");
  return out;
}

void fill_index(int bins, std::array<int32_t, 256>& qb, std::array<int32_t, 256>& qg, std::array<int32_t, 256>& qr) {
  const int shift = 8 - log2_exact(bins);
  for (int v = 0; v < 256; ++v) {
    qb[static_cast<size_t>(v)] = (v >> shift) * bins * bins;
    qg[static_cast<size_t>(v)] = (v >> shift) * bins;
    qr[static_cast<size_t>(v)] = v >> shift;
  }
}

}  // namespace

int log2_exact(int bins) {
  for (int k = 1; k <= 8; ++k)
    if ((1 << k) == bins) return k;
  return -1;
}

void blend_histogram(std::vector<double>& model, const std::vector<double>& sample, double total, double rate,
                     bool first) {
  const double keep = first ? 0.0 : 1.0 - rate, add = (first ? 1.0 : rate) / total;
  if (model.empty()) model.assign(sample.size(), 0.0);
  for (size_t i = 0; i < model.size(); ++i) model[i] = keep * model[i] + add * sample[i];
}

SkinHistogram::SkinHistogram(int bins) : bins_(bins), shift_(8 - log2_exact(bins)) {
  if (log2_exact(bins) < 1) throw SkinModelError("bins per channel must be a power of two from 2 to 256, not " + std::to_string(bins));
  skin_.assign(static_cast<size_t>(bins) * bins * bins, 0.0);
  non_ = skin_;
}

SkinModel SkinModel::train(const SkinHistogram& hist, const SkinTrainOptions& options) {
  if (hist.skin_total() <= 0 || hist.non_skin_total() <= 0)
    throw SkinModelError("training needs both skin and non-skin pixels");
  const int bins = hist.bins();
  const std::vector<double> s = smooth_histogram(hist.skin_counts(), bins, options.smoothing_sigma);
  const std::vector<double> n = smooth_histogram(hist.non_skin_counts(), bins, options.smoothing_sigma);
  SkinModel m;
  m.bins_ = bins;
  m.description_ = trim_end(options.description);
  m.table_.resize(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    const double total = s[i] + n[i];
    const double p = total > 1e-12 ? s[i] / total : 0.0;
    m.table_[i] = static_cast<uint8_t>(std::lround(p * 255.0));
  }
  double s_total = 0, n_total = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    s_total += s[i];
    n_total += n[i];
  }
  m.skin_prior_ = s_total / (s_total + n_total);
  // Stored rounded (as in the file), so a trained model and the same model loaded back are the same.
  m.skin_likelihood_.resize(s.size());
  m.non_likelihood_.resize(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    m.skin_likelihood_[i] = decode_likelihood(encode_likelihood(s[i] / s_total));
    m.non_likelihood_[i] = decode_likelihood(encode_likelihood(n[i] / n_total));
  }
  m.build_index();
  return m;
}

void SkinModel::build_index() { fill_index(bins_, qb_, qg_, qr_); }

void SkinModel::save(const std::string& path) const {
  std::ofstream f(path);
  if (!f) throw SkinModelError("cannot write " + path);
  YAML::Emitter e;
  e << YAML::BeginMap << YAML::Key << "format" << YAML::Value << kFormat;
  e << YAML::Key << "bins" << YAML::Value << bins_;
  e << YAML::Key << "description" << YAML::Value << YAML::Literal << description_;
  e << YAML::Key << "table_hex" << YAML::Value << YAML::Literal << to_hex(table_);
  if (has_likelihoods()) {
    auto encode = [](const std::vector<float>& l) {
      std::vector<uint8_t> q(l.size());
      for (size_t i = 0; i < l.size(); ++i) q[i] = encode_likelihood(l[i]);
      return q;
    };
    e << YAML::Key << "skin_prior" << YAML::Value << skin_prior_;
    e << YAML::Key << "skin_likelihood_hex" << YAML::Value << YAML::Literal << to_hex(encode(skin_likelihood_));
    e << YAML::Key << "non_likelihood_hex" << YAML::Value << YAML::Literal << to_hex(encode(non_likelihood_));
  }
  e << YAML::EndMap;
  f << "# gesture-pilot skin model: P(skin | B,G,R) x 255 per histogram bin, index (b*bins + g)*bins + r.\n"
    << "# Written by gpilot-skin-train; read by gpilot-hands (hands.skin.model).\n"
    << e.c_str() << "\n";
  if (!f) throw SkinModelError("error writing " + path);
}

SkinModel SkinModel::load(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw SkinModelError("cannot read skin model " + path);
  } catch (const YAML::Exception& ex) {
    throw SkinModelError(path + ": not YAML: " + ex.what());
  }
  try {
    if (!root.IsMap() || !root["format"] || root["format"].as<std::string>() != kFormat)
      throw SkinModelError(path + ": not a skin model (format must be " + kFormat + ")");
    SkinModel m;
    m.bins_ = root["bins"].as<int>();
    if (log2_exact(m.bins_) < 1) throw SkinModelError(path + ": bins must be a power of two from 2 to 256");
    if (root["description"]) m.description_ = trim_end(root["description"].as<std::string>());
    const size_t n = static_cast<size_t>(m.bins_) * m.bins_ * m.bins_;
    m.table_ = from_hex(root["table_hex"].as<std::string>(), path + ": table_hex");
    if (m.table_.size() != n)
      throw SkinModelError(path + ": table has " + std::to_string(m.table_.size()) + " entries, bins^3 = " + std::to_string(n));
    if (root["skin_likelihood_hex"] || root["non_likelihood_hex"]) {
      m.skin_prior_ = root["skin_prior"].as<double>();
      if (!(m.skin_prior_ > 0 && m.skin_prior_ < 1)) throw SkinModelError(path + ": skin_prior must be in (0, 1)");
      for (auto [key, out] : {std::pair{"skin_likelihood_hex", &m.skin_likelihood_}, std::pair{"non_likelihood_hex", &m.non_likelihood_}}) {
        const auto q = from_hex(root[key].as<std::string>(), path + ": " + key);
        if (q.size() != n)
          throw SkinModelError(path + ": " + key + " has " + std::to_string(q.size()) + " entries, bins^3 = " + std::to_string(n));
        out->resize(n);
        for (size_t i = 0; i < n; ++i) (*out)[i] = decode_likelihood(q[i]);
      }
    }
    m.build_index();
    return m;
  } catch (const YAML::Exception& ex) {
    throw SkinModelError(path + ": bad skin model: " + ex.what());
  }
}

int SkinModel::threshold_level(double threshold) {
  return static_cast<int>(std::floor(threshold * 255.0));
}

void SkinModel::levels(const cv::Mat& bgr, cv::Mat& out) const {
  CV_Assert(bgr.type() == CV_8UC3 && !empty());
  out.create(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y) {
    const uint8_t* p = bgr.ptr<uint8_t>(y);
    uint8_t* o = out.ptr<uint8_t>(y);
    for (int x = 0; x < bgr.cols; ++x, p += 3) o[x] = level(p[0], p[1], p[2]);
  }
}

SkinClassifier::SkinClassifier(const SkinModel& model, double threshold) {
  if (model.empty()) throw SkinModelError("skin classifier needs a trained model");
  const int t = SkinModel::threshold_level(threshold);
  mask_table_.resize(model.table().size());
  for (size_t i = 0; i < mask_table_.size(); ++i) mask_table_[i] = model.table()[i] > t ? 1 : 0;
  fill_index(model.bins(), qb_, qg_, qr_);
  bits_ = log2_exact(model.bins());
  shift_ = 8 - bits_;
}

SkinClassifier::SkinClassifier(int bins, std::vector<uint8_t> mask_table) : mask_table_(std::move(mask_table)) {
  if (log2_exact(bins) < 1) throw SkinModelError("bins per channel must be a power of two from 2 to 256");
  if (mask_table_.size() != static_cast<size_t>(bins) * bins * bins) throw SkinModelError("skin table size is not bins^3");
  fill_index(bins, qb_, qg_, qr_);
  bits_ = log2_exact(bins);
  shift_ = 8 - bits_;
}

void SkinClassifier::classify(const cv::Mat& bgr, cv::Mat& mask) const {
  CV_Assert(bgr.type() == CV_8UC3 && !empty());
  mask.create(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y) {
    const uint8_t* p = bgr.ptr<uint8_t>(y);
    uint8_t* o = mask.ptr<uint8_t>(y);
    // Shifts rather than the three index tables of is_skin(): the same index, fewer loads in the hot loop.
    const uint8_t* table = mask_table_.data();
    const int s = shift_, b1 = bits_, b2 = 2 * bits_;
    for (int x = 0; x < bgr.cols; ++x, p += 3)
      o[x] = table[(static_cast<unsigned>(p[0] >> s) << b2) | (static_cast<unsigned>(p[1] >> s) << b1) | (p[2] >> s)];
  }
}

}  // namespace gpilot
