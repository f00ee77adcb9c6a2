// Nonparametric histogram skin model (the paper's Conaire 2007 approach, trained on our own labelled
// pixels): B,G,R quantised to `bins` levels per channel -> one table index -> P(skin | colour), stored as a
// byte (0..255 = P x 255). Classification is one table lookup per pixel and a threshold.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace gpilot {

class SkinModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// k for bins per channel = 2^k (k 1..8), else -1.
int log2_exact(int bins);

// A 3-D Gaussian blur (sigma in bins, truncated at 3 sigma, zero outside) of a bins^3 histogram, b-major.
std::vector<double> smooth_histogram(std::vector<double> v, int bins, double sigma);
// A learnt colour histogram with decay: `sample` (counts, `total` of them) blended into `model` (normalised) at
// `rate`, or taking its place when `first`. An empty model starts at zero.
void blend_histogram(std::vector<double>& model, const std::vector<double>& sample, double total, double rate,
                     bool first);

// Counts of skin and non-skin colours, the raw material of a SkinModel.
class SkinHistogram {
 public:
  explicit SkinHistogram(int bins);  // bins: a power of two, 2..256
  int bins() const { return bins_; }
  int index(uint8_t b, uint8_t g, uint8_t r) const {
    return ((b >> shift_) * bins_ + (g >> shift_)) * bins_ + (r >> shift_);
  }
  void add(uint8_t b, uint8_t g, uint8_t r, bool skin, double weight = 1.0) {
    (skin ? skin_ : non_)[static_cast<size_t>(index(b, g, r))] += weight;
    (skin ? n_skin_ : n_non_) += weight;
  }
  double skin_total() const { return n_skin_; }
  double non_skin_total() const { return n_non_; }
  const std::vector<double>& skin_counts() const { return skin_; }
  const std::vector<double>& non_skin_counts() const { return non_; }

 private:
  int bins_;
  int shift_;
  std::vector<double> skin_, non_;
  double n_skin_ = 0, n_non_ = 0;
};

struct SkinTrainOptions {
  double smoothing_sigma = 1.0;  //!< Gaussian blur of both histograms, in bins (0 = none)
  std::string description;       //!< how the model was made (sources, options), stored in the file
};

class SkinModel {
 public:
  SkinModel() = default;

  // Bayes: P(skin|c) = P(c|skin)P(skin) / (P(c|skin)P(skin) + P(c|non)P(non)) with the class priors from the
  // counts, i.e. smoothed skin count / (smoothed skin + smoothed non-skin count); 0 where both are empty.
  static SkinModel train(const SkinHistogram& hist, const SkinTrainOptions& options);

  // YAML file: bins, description, the table as hex (2 digits a bin, b-major then g then r), and the two class
  // likelihoods P(c|skin), P(c|not) as -log2 in 1/8 bit steps (2 hex digits a bin) with the skin prior, which
  // the adaptive model (SkinAdapter) needs. A file without them still loads (has_likelihoods() false).
  void save(const std::string& path) const;
  static SkinModel load(const std::string& path);  // throws SkinModelError with the reason

  bool empty() const { return table_.empty(); }
  int bins() const { return bins_; }
  const std::string& description() const { return description_; }
  const std::vector<uint8_t>& table() const { return table_; }

  bool has_likelihoods() const { return !skin_likelihood_.empty(); }
  const std::vector<float>& skin_likelihood() const { return skin_likelihood_; }  //!< P(c | skin), sums to ~1
  const std::vector<float>& non_likelihood() const { return non_likelihood_; }    //!< P(c | not skin), sums to ~1
  double skin_prior() const { return skin_prior_; }                               //!< P(skin) of the training counts

  // The table index of one colour.
  int bin(uint8_t b, uint8_t g, uint8_t r) const { return qb_[b] + qg_[g] + qr_[r]; }
  // P(skin) x 255 of one colour.
  uint8_t level(uint8_t b, uint8_t g, uint8_t r) const {
    return table_[static_cast<size_t>(qb_[b] + qg_[g] + qr_[r])];
  }
  // The byte level a probability threshold corresponds to: skin iff level > threshold_level(t).
  static int threshold_level(double threshold);

  // P(skin) x 255 for every pixel of a BGR image (CV_8UC3) into out (CV_8UC1).
  void levels(const cv::Mat& bgr, cv::Mat& out) const;

 private:
  void build_index();

  int bins_ = 0;
  std::string description_;
  std::vector<uint8_t> table_;
  std::vector<float> skin_likelihood_, non_likelihood_;
  double skin_prior_ = 0;
  std::array<int32_t, 256> qb_{}, qg_{}, qr_{};  // per-channel parts of the table index
};

// Binary skin classifier: a SkinModel and a threshold folded into one 0/1 table.
class SkinClassifier {
 public:
  SkinClassifier() = default;
  SkinClassifier(const SkinModel& model, double threshold);
  // From a ready 0/1 table of bins^3 entries (b-major), e.g. an adapted model's.
  SkinClassifier(int bins, std::vector<uint8_t> mask_table);

  bool empty() const { return mask_table_.empty(); }
  int bins() const { return 1 << bits_; }  //!< per channel
  bool is_skin(uint8_t b, uint8_t g, uint8_t r) const {
    return mask_table_[static_cast<size_t>(qb_[b] + qg_[g] + qr_[r])] != 0;
  }
  // mask (CV_8UC1, same size as bgr): 1 = skin, 0 = not, for the pixels of bgr (CV_8UC3).
  void classify(const cv::Mat& bgr, cv::Mat& mask) const;
  const std::vector<uint8_t>& mask_table() const { return mask_table_; }

 private:
  std::vector<uint8_t> mask_table_;
  std::array<int32_t, 256> qb_{}, qg_{}, qr_{};
  int shift_ = 0, bits_ = 0;  // index = (b >> shift) << 2 bits | (g >> shift) << bits | r >> shift
};

}  // namespace gpilot
