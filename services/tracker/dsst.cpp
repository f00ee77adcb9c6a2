// DSST translation and scale filters (see dsst.hpp). Conventions: a pixel i covers [i, i+1) in continuous
// frame coordinates, so a box's centre is x + w/2 and a crop resized by cv::resize maps u -> x0 + u * f.
#include "dsst.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace gpilot {
namespace {

constexpr int kGreyChannel = Fhog::kChannels;  // channel 31 of the translation features
constexpr int kTranslationChannels = Fhog::kChannels + 1;

std::vector<float> hann(int n) {
  std::vector<float> w(static_cast<size_t>(n), 1.0f);
  if (n > 1)
    for (int i = 0; i < n; ++i)
      w[static_cast<size_t>(i)] = static_cast<float>(0.5 * (1.0 - std::cos(2.0 * M_PI * i / (n - 1))));
  return w;
}

// Copies the integer rectangle r of frame into out, replicating the border where r leaves the frame.
void crop_replicate(const cv::Mat& frame, const cv::Rect& r, cv::Mat& out) {
  const cv::Rect inside = r & cv::Rect(0, 0, frame.cols, frame.rows);
  if (inside == r) {
    out = frame(r);
    return;
  }
  // The track centre is kept inside the frame, so the crop always overlaps it.
  CV_Assert(inside.area() > 0);
  // out may still be a view into the frame from a crop that was inside: copyMakeBorder would write this crop
  // into the frame itself when the sizes match (the wide search's windows are all one size).
  if (out.data >= frame.datastart && out.data < frame.dataend) out.release();
  cv::copyMakeBorder(frame(inside), out, inside.y - r.y, r.br().y - inside.br().y, inside.x - r.x,
                     r.br().x - inside.br().x, cv::BORDER_REPLICATE);
}

// A crop of about `size` frame pixels centred on `centre`, resized to `out_size`. Shrinking is done in exact
// halvings (INTER_AREA at 2x: OpenCV's vectorised path; the crop is rounded to a multiple of their product)
// while the ratio left is 2 or more, then a bilinear step of less than 2x: anti-aliased, and much cheaper than
// INTER_AREA at an arbitrary ratio (or at an integer one above 2: at 3x, 5x the cost of a halving of the same
// crop). Returns the crop's top-left corner and frame pixels per output pixel, so that output pixel coordinate
// u maps to frame x0 + u * f exactly. tmp and out are the steps' buffers (swapped as needed).
std::pair<cv::Point2d, cv::Point2d> crop_resized(const cv::Mat& frame, cv::Point2d centre, cv::Size2d size,
                                                 cv::Size out_size, cv::Mat& crop, cv::Mat& tmp, cv::Mat& out) {
  const double ratio = std::min(size.width / out_size.width, size.height / out_size.height);
  int k = 1;
  while (2 * k <= ratio) k *= 2;
  const int cw = k * std::max(1, static_cast<int>(std::lround(size.width / k)));
  const int ch = k * std::max(1, static_cast<int>(std::lround(size.height / k)));
  const cv::Rect r(static_cast<int>(std::lround(centre.x - cw / 2.0)), static_cast<int>(std::lround(centre.y - ch / 2.0)), cw, ch);
  crop_replicate(frame, r, crop);
  const cv::Mat* src = &crop;
  for (int f = k; f > 1; f /= 2) {
    cv::Mat& dst = src == &tmp ? out : tmp;
    cv::resize(*src, dst, cv::Size(src->cols / 2, src->rows / 2), 0, 0, cv::INTER_AREA);
    src = &dst;
  }
  if (src == &out) std::swap(out, tmp), src = &tmp;
  if (src->size() == out_size)
    src->copyTo(out);
  else
    cv::resize(*src, out, out_size, 0, 0, cv::INTER_LINEAR);
  return {cv::Point2d(r.x, r.y), cv::Point2d(static_cast<double>(cw) / out_size.width, static_cast<double>(ch) / out_size.height)};
}

// acc = (1 - rate) acc + rate * G ⊙ conj(F), elementwise over complex (CV_32FC2) arrays of equal size;
// rate 1 assigns.
void blend_numerator(cv::Mat& acc, const cv::Mat& g, const cv::Mat& f, float rate) {
  const int n = f.rows * f.cols;
  const float* gp = g.ptr<float>();
  const float* fp = f.ptr<float>();
  float* ap = acc.ptr<float>();
  const float keep = 1.0f - rate;
  for (int i = 0; i < n; ++i) {
    const float gr = gp[2 * i], gi = gp[2 * i + 1], fr = fp[2 * i], fi = fp[2 * i + 1];
    ap[2 * i] = keep * ap[2 * i] + rate * (gr * fr + gi * fi);
    ap[2 * i + 1] = keep * ap[2 * i + 1] + rate * (gi * fr - gr * fi);
  }
}

// Sub-cell offset of a peak from three samples around it: a Gaussian fit (exact for the Gaussian-shaped
// response the filter is trained for) when all three are positive, else a parabola.
double peak_offset(double a, double b, double c) {
  if (a > 0 && b > 0 && c > 0) {
    a = std::log(a);
    b = std::log(b);
    c = std::log(c);
  }
  const double den = a - 2.0 * b + c;
  if (den >= 0) return 0.0;
  return std::clamp(0.5 * (a - c) / den, -0.5, 0.5);
}

}  // namespace

Dsst::Dsst(const DsstParams& params) : p_(params) {
  if (p_.cell_size < 1 || p_.number_of_scales < 1 || p_.scale_step <= 1.0 || p_.lambda <= 0 ||
      p_.max_model_area < p_.min_model_area)
    throw std::invalid_argument("Dsst: invalid parameters");
}

DsstEstimate Dsst::estimate() const {
  DsstEstimate e;
  const cv::Size2d sz(base_size_.width * scale_, base_size_.height * scale_);
  e.box = cv::Rect2d(pos_.x - sz.width / 2, pos_.y - sz.height / 2, sz.width, sz.height);
  e.psr = psr_;
  e.scale = scale_;
  return e;
}

void Dsst::restore(const DsstEstimate& e) {
  if (!initialized_) throw std::logic_error("Dsst::restore before init");
  pos_ = cv::Point2d(e.box.x + e.box.width / 2, e.box.y + e.box.height / 2);
  scale_ = std::clamp(e.scale, min_scale_, max_scale_);
  psr_ = e.psr;
  have_detection_ = false;  // the next learn() samples at the restored estimate, not at an older detection
}

void Dsst::init(const cv::Mat& frame, const cv::Rect2d& box) {
  initialized_ = false;
  check_frame(frame, "Dsst::init");
  const cv::Point2d c(box.x + box.width / 2, box.y + box.height / 2);
  if (!std::isfinite(box.x) || !std::isfinite(box.y) || !std::isfinite(box.width) || !std::isfinite(box.height) ||
      box.width < 2 || box.height < 2 || c.x < 0 || c.y < 0 || c.x >= frame.cols || c.y >= frame.rows)
    throw std::invalid_argument("Dsst::init: box must be at least 2x2 pixels with its centre inside the frame");

  const int cell = p_.cell_size;
  frame_size_ = frame.size();
  pos_ = c;
  base_size_ = box.size();
  scale_ = 1.0;
  psr_ = 0.0;
  good_psr_ = 0.0;

  const double area = box.area();
  model_factor_ = 1.0;
  if (area > p_.max_model_area) model_factor_ = std::sqrt(p_.max_model_area / area);
  if (area < p_.min_model_area) model_factor_ = std::sqrt(p_.min_model_area / area);
  window_frame_ = cv::Size2d(box.width * (1.0 + p_.padding), box.height * (1.0 + p_.padding));
  if (p_.min_window_side > 0) {
    const double side = p_.min_window_side * (1.0 + p_.padding) * std::sqrt(box.area());
    window_frame_ = cv::Size2d(std::max(window_frame_.width, side), std::max(window_frame_.height, side));
  }
  cells_ = cv::Size(cv::getOptimalDFTSize(std::max(4, static_cast<int>(std::lround(window_frame_.width * model_factor_ / cell)))),
                    cv::getOptimalDFTSize(std::max(4, static_cast<int>(std::lround(window_frame_.height * model_factor_ / cell)))));
  sigma_cells_ = std::sqrt(area) * model_factor_ * p_.output_sigma_factor / cell;

  const auto wx = hann(cells_.width), wy = hann(cells_.height);
  cos_window_.create(cells_, CV_32F);
  for (int y = 0; y < cells_.height; ++y)
    for (int x = 0; x < cells_.width; ++x)
      cos_window_.at<float>(y, x) = wy[static_cast<size_t>(y)] * wx[static_cast<size_t>(x)];

  // Scale filter: factors a^n, n = -(S-1)/2 .. (S-1)/2, label peaked at n = 0. σ follows the DSST code
  // (scale_sigma = nScales / sqrt(33) * scale_sigma_factor): 1.44 scales for the published 33 and 1/4.
  // fDSST (scale_samples n < S): n factors over the same range, a^((k - (n-1)/2) S/n); σ in the same units
  // (steps of a), so both filters learn the same label shape.
  const int S = p_.number_of_scales;
  const int mid = (S - 1) / 2;
  const int n = p_.scale_samples > 0 && p_.scale_samples < S ? p_.scale_samples : S;
  scale_interp_ = n < S;
  scale_factors_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    scale_factors_[static_cast<size_t>(i)] =
        std::pow(p_.scale_step, scale_interp_ ? (i - (n - 1) / 2) * static_cast<double>(S) / n : i - mid);
  scale_twiddles_.resize(static_cast<size_t>(2 * (n / 2 + 1) * n));
  for (int k = 0; k <= n / 2; ++k)
    for (int s = 0; s < n; ++s) {  // e^(-2 pi i k s / n), as cv::dft's forward transform
      const double a = -2.0 * M_PI * ((k * s) % n) / n;
      scale_twiddles_[static_cast<size_t>(2 * (k * n + s))] = static_cast<float>(std::cos(a));
      scale_twiddles_[static_cast<size_t>(2 * (k * n + s) + 1)] = static_cast<float>(std::sin(a));
    }
  scale_window_ = n % 2 == 0 ? hann(n + 1) : hann(n);
  if (n % 2 == 0) scale_window_.erase(scale_window_.begin());
  if (n == 1) scale_window_.assign(1, 1.0f);
  const double scale_sigma = S / std::sqrt(33.0) * p_.scale_sigma_factor;
  scale_labels_f_.resize(static_cast<size_t>(S));
  interp_exp_.assign(static_cast<size_t>(S), 0);
  for (int m = 0; m < S; ++m) interp_exp_[static_cast<size_t>(m)] = m <= S / 2 ? m : m - S;
  label_no_change_ = scale_interp_ ? 0 : mid;
  for (int c = 0; c < S; ++c) {
    cv::Mat ys(1, n, CV_32F);
    for (int i = 0; i < n; ++i) {
      double d = i - c;
      if (scale_interp_) {
        // Response index i is a change of t_i sampled steps (circular: index 0 none, the last -1), S/n each;
        // the label peaks at the change interp_exp_[c], distances taken around the circle of S steps.
        const double t = (i <= n / 2 ? i : i - n) * static_cast<double>(S) / n;
        d = t - interp_exp_[static_cast<size_t>(c)];
        d -= S * std::round(d / S);
      }
      ys.at<float>(0, i) = static_cast<float>(std::exp(-0.5 * d * d / (scale_sigma * scale_sigma)));
    }
    cv::dft(ys, scale_labels_f_[static_cast<size_t>(c)], cv::DFT_ROWS | cv::DFT_COMPLEX_OUTPUT);
  }
  const double sf = area > p_.scale_model_max_area ? std::sqrt(p_.scale_model_max_area / area) : 1.0;
  scale_model_sz_ = cv::Size(std::max(2 * cell, static_cast<int>(box.width * sf)),
                             std::max(2 * cell, static_cast<int>(box.height * sf)));
  const double log_a = std::log(p_.scale_step);
  min_scale_ = std::pow(p_.scale_step,
                        std::ceil(std::log(std::max(5.0 / window_frame_.width, 5.0 / window_frame_.height)) / log_a));
  max_scale_ = std::pow(p_.scale_step,
                        std::floor(std::log(std::min(frame.cols / box.width, frame.rows / box.height)) / log_a));
  max_scale_ = std::max(max_scale_, 1.0);
  min_scale_ = std::min(min_scale_, 1.0);

  const Sample s = translation_features(frame, pos_, scale_);
  learn_translation(s, true);
  colour_ = p_.colour_weight > 0 && frame.channels() == 3;
  if (colour_) learn_colour(s, true);
  scale_features(frame, pos_, scale_);
  learn_scale(true, label_no_change_);
  have_detection_ = false;
  initialized_ = true;
}

namespace {
constexpr int kColourBins = 32 * 32 * 32;
inline int colour_bin(const cv::Vec3b& p) { return (p[0] >> 3) * 1024 + (p[1] >> 3) * 32 + (p[2] >> 3); }
}  // namespace

// Where the target is in the translation sample patch_, in patch pixels (its centre at the estimate pos_).
cv::Rect2d Dsst::target_in_patch(const Sample& s) const {
  const cv::Point2d c((pos_.x - s.centre.x) / s.frame_per_model.x, (pos_.y - s.centre.y) / s.frame_per_model.y);
  const cv::Size2d sz(base_size_.width * scale_ / s.frame_per_model.x, base_size_.height * scale_ / s.frame_per_model.y);
  return cv::Rect2d(c.x - sz.width / 2, c.y - sz.height / 2, sz.width, sz.height);
}

void Dsst::BinCounts::add(int b) {
  float& c = n[static_cast<size_t>(b)];
  if (c == 0) counted.push_back(b);
  c += 1;
  total += 1;
}

void Dsst::BinCounts::clear() {
  for (const int b : counted) n[static_cast<size_t>(b)] = 0.0f;
  counted.clear();
  total = 0;
}

// h = (1 - rate) h + rate * counts / total, bin by bin, as one pass over every bin did: the decay (the whole update
// of a bin this frame left empty) over all of them, then each bin the frame counted. Bit for bit the same as that
// pass, without its 65536 double divisions and two 128 KB clears a frame (a twentieth of the tracker's time).
void Dsst::BinCounts::blend_into(std::vector<float>& h, float rate) const {
  const float keep = 1.0f - rate;
  for (float& v : h) v *= keep;
  for (const int b : counted) h[static_cast<size_t>(b)] += rate * static_cast<float>(n[static_cast<size_t>(b)] / total);
}

// Foreground: the target box shrunk by a tenth each side (Staple's inner region, less background at its
// corners); background: the window outside the whole target box.
void Dsst::learn_colour(const Sample& s, bool first) {
  if (first) {
    fg_hist_.assign(kColourBins, 0.0f);
    bg_hist_.assign(kColourBins, 0.0f);
    fg_counts_ = BinCounts{std::vector<float>(kColourBins, 0.0f), {}, 0};
    bg_counts_ = BinCounts{std::vector<float>(kColourBins, 0.0f), {}, 0};
  }
  if (patch_.type() != CV_8UC3) return;  // a grey frame within a colour track: not learnt
  const cv::Rect2d t = target_in_patch(s);
  const cv::Rect2d inner(t.x + 0.1 * t.width, t.y + 0.1 * t.height, 0.8 * t.width, 0.8 * t.height);
  for (int y = 0; y < patch_.rows; ++y) {
    const cv::Vec3b* row = patch_.ptr<cv::Vec3b>(y);
    for (int x = 0; x < patch_.cols; ++x) {
      const cv::Point2d c(x + 0.5, y + 0.5);
      if (inner.contains(c))
        fg_counts_.add(colour_bin(row[x]));
      else if (!t.contains(c))
        bg_counts_.add(colour_bin(row[x]));
    }
  }
  // A window all target or all border has nothing to learn from.
  if (fg_counts_.total > 0 && bg_counts_.total > 0) {
    const float rate = first ? 1.0f : static_cast<float>(p_.colour_learning_rate);
    fg_counts_.blend_into(fg_hist_, rate);
    bg_counts_.blend_into(bg_hist_, rate);
  }
  fg_counts_.clear();
  bg_counts_.clear();
}

// Per pixel P(target | colour) = fg / (fg + bg); per cell of the window, its Gaussian-weighted mean around
// there (colour_centre_sigma; 0: the mean over a target-sized box, Staple's), in the correlation response's
// coordinates (the label peaks at the target's cell).
void Dsst::colour_response(const Sample& s) {
  if (patch_.type() != CV_8UC3) {  // a grey frame within a colour track: no colour evidence
    colour_resp_ = cv::Mat::zeros(cells_, CV_32F);
    return;
  }
  likelihood_.create(patch_.size(), CV_32F);
  for (int y = 0; y < patch_.rows; ++y) {
    const cv::Vec3b* row = patch_.ptr<cv::Vec3b>(y);
    float* out = likelihood_.ptr<float>(y);
    for (int x = 0; x < patch_.cols; ++x) {
      const size_t b = static_cast<size_t>(colour_bin(row[x]));
      const float f = fg_hist_[b], g = bg_hist_[b];
      out[x] = f + g > 0 ? f / (f + g) : 0.0f;
    }
  }
  cv::resize(likelihood_, colour_cells_, cells_, 0, 0, cv::INTER_AREA);
  const cv::Rect2d t = target_in_patch(s);
  const int cell = p_.cell_size;
  if (p_.colour_centre_sigma > 0) {
    // At least 0.3 cells: narrower, OpenCV's kernel is a single tap.
    cv::GaussianBlur(colour_cells_, colour_resp_, cv::Size(), std::max(0.3, p_.colour_centre_sigma * t.width / cell),
                     std::max(0.3, p_.colour_centre_sigma * t.height / cell), cv::BORDER_CONSTANT);
  } else {
    const cv::Size k(std::max(1, static_cast<int>(std::lround(t.width / cell))), std::max(1, static_cast<int>(std::lround(t.height / cell))));
    cv::boxFilter(colour_cells_, colour_resp_, CV_32F, k, cv::Point(-1, -1), true, cv::BORDER_CONSTANT);
  }
}

Dsst::Sample Dsst::translation_features(const cv::Mat& frame, cv::Point2d pos, double scale) {
  const int cell = p_.cell_size;
  const cv::Size model(cells_.width * cell, cells_.height * cell);
  const auto [origin, fpm] = crop_resized(frame, pos, window_frame_ * scale, model, crop_, shrunk_, patch_);

  patch_features(patch_, cells_, feats_);
  window_spectra(feats_, cv::Rect(cv::Point(), cells_));
  return Sample{origin, fpm};
}

void Dsst::patch_features(const cv::Mat& patch, cv::Size cells, std::vector<cv::Mat>& out) {
  out.resize(kTranslationChannels);
  fhog_.compute(patch, p_.cell_size, out, 0);
  if (patch.channels() == 3) cv::cvtColor(patch, grey_, cv::COLOR_BGR2GRAY);
  cv::resize(patch.channels() == 3 ? grey_ : patch, grey_cells_, cells, 0, 0, cv::INTER_AREA);
  grey_cells_.convertTo(out[kGreyChannel], CV_32F, 1.0 / 255.0, -0.5);
}

void Dsst::window_spectra(const std::vector<cv::Mat>& features, const cv::Rect& window) {
  feats_.resize(kTranslationChannels);
  feats_f_.resize(kTranslationChannels);
  for (int l = 0; l < kTranslationChannels; ++l) {
    cv::multiply(features[static_cast<size_t>(l)](window), cos_window_, feats_[static_cast<size_t>(l)]);
    cv::dft(feats_[static_cast<size_t>(l)], feats_f_[static_cast<size_t>(l)], cv::DFT_COMPLEX_OUTPUT);
  }
}

void Dsst::gaussian_label(cv::Point2d centre_cells) {
  label_.create(cells_, CV_32F);
  const double k = -0.5 / (sigma_cells_ * sigma_cells_);
  for (int y = 0; y < cells_.height; ++y) {
    const double dy = y - centre_cells.y;
    float* row = label_.ptr<float>(y);
    for (int x = 0; x < cells_.width; ++x) {
      const double dx = x - centre_cells.x;
      row[x] = static_cast<float>(std::exp(k * (dx * dx + dy * dy)));
    }
  }
  cv::dft(label_, label_f_, cv::DFT_COMPLEX_OUTPUT);
}

void Dsst::learn_translation(const Sample& s, bool first) {
  // The label peaks where the target centre really is in this sample (the crop is rounded to whole
  // pixels), so the filter learns no half-pixel bias.
  const double cell = p_.cell_size;
  gaussian_label(cv::Point2d((pos_.x - s.centre.x) / s.frame_per_model.x / cell - 0.5,
                             (pos_.y - s.centre.y) / s.frame_per_model.y / cell - 0.5));
  const float rate = first ? 1.0f : static_cast<float>(p_.learning_rate);
  num_.resize(kTranslationChannels);
  if (first) {
    for (auto& a : num_) a = cv::Mat::zeros(cells_, CV_32FC2);
    den_ = cv::Mat::zeros(cells_, CV_32F);
  }
  const int n = cells_.area();
  float* d = den_.ptr<float>();
  for (int i = 0; i < n; ++i) d[i] *= 1.0f - rate;
  for (int l = 0; l < kTranslationChannels; ++l) {
    const cv::Mat& f = feats_f_[static_cast<size_t>(l)];
    blend_numerator(num_[static_cast<size_t>(l)], label_f_, f, rate);
    const float* fp = f.ptr<float>();
    for (int i = 0; i < n; ++i) d[i] += rate * (fp[2 * i] * fp[2 * i] + fp[2 * i + 1] * fp[2 * i + 1]);
  }
}

void Dsst::scale_features(const cv::Mat& frame, cv::Point2d pos, double scale) {
  const int S = static_cast<int>(scale_factors_.size());
  const double amax = scale_factors_.back();
  // One anti-aliased shrink of the largest sample, then each scale is a bilinear warp of that small image.
  const cv::Size inter(static_cast<int>(std::ceil(scale_model_sz_.width * amax)),
                       static_cast<int>(std::ceil(scale_model_sz_.height * amax)));
  const auto [origin, fpi] = crop_resized(frame, pos, base_size_ * (scale * amax), inter, crop_, shrunk_, scale_inter_);
  const double fx = 1.0 / fpi.x, fy = 1.0 / fpi.y;

  const int cell = p_.cell_size;
  const int d = Fhog::kChannels * (scale_model_sz_.height / cell) * (scale_model_sz_.width / cell);
  scale_x_.create(S, d, CV_32F);
  for (int s = 0; s < S; ++s) {
    const double a = scale_factors_[static_cast<size_t>(s)];
    const double kx = base_size_.width * scale * a / scale_model_sz_.width;
    const double ky = base_size_.height * scale * a / scale_model_sz_.height;
    const cv::Matx23d m(fx * kx, 0, fx * (pos.x + (0.5 - scale_model_sz_.width / 2.0) * kx - origin.x) - 0.5,  //
                        0, fy * ky, fy * (pos.y + (0.5 - scale_model_sz_.height / 2.0) * ky - origin.y) - 0.5);
    cv::warpAffine(scale_inter_, scale_patch_, m, scale_model_sz_, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                   cv::BORDER_REPLICATE);
    fhog_.compute(scale_patch_, cell, scale_fhog_, 0);
    const float w = scale_window_[static_cast<size_t>(s)];
    float* x = scale_x_.ptr<float>(s);
    for (int c = 0; c < Fhog::kChannels; ++c) {
      const cv::Mat& m_c = scale_fhog_[static_cast<size_t>(c)];
      const float* src = m_c.ptr<float>();
      const int n = m_c.rows * m_c.cols;
      for (int i = 0; i < n; ++i) *x++ = w * src[i];
    }
  }
  scale_spectrum();
}

// The DFT over the scales of every feature of the scale samples, by its definition: cv::dft(DFT_ROWS) on the
// d x S samples spent 150 us a frame (a quarter of the scale filter's time) on one 19-point DFT (a prime length:
// no fast radix) per feature; summing the S sample rows into each frequency's row is a vectorised loop over d.
// Only the frequencies 0..S/2 are kept: the samples are real, so the others are their conjugates, and so are
// the filter's numerator and response there (its label is real too).
void Dsst::scale_spectrum() {
  const int S = scale_x_.rows, d = scale_x_.cols, K = S / 2 + 1;
  scale_x_f_.create(K, d, CV_32FC2);
  dft_re_.resize(static_cast<size_t>(d));
  dft_im_.resize(static_cast<size_t>(d));
  float* re = dft_re_.data();
  float* im = dft_im_.data();
  for (int k = 0; k < K; ++k) {
    std::fill(dft_re_.begin(), dft_re_.end(), 0.0f);
    std::fill(dft_im_.begin(), dft_im_.end(), 0.0f);
    for (int s = 0; s < S; ++s) {
      const float c = scale_twiddles_[static_cast<size_t>(2 * (k * S + s))];
      const float sn = scale_twiddles_[static_cast<size_t>(2 * (k * S + s) + 1)];
      const float* x = scale_x_.ptr<float>(s);
      for (int j = 0; j < d; ++j) {
        re[j] += c * x[j];
        im[j] += sn * x[j];
      }
    }
    float* out = scale_x_f_.ptr<float>(k);
    for (int j = 0; j < d; ++j) {
      out[2 * j] = re[j];
      out[2 * j + 1] = im[j];
    }
  }
}

void Dsst::learn_scale(bool first, int label_centre) {
  const float* label_f = scale_labels_f_[static_cast<size_t>(label_centre)].ptr<float>();
  const int K = scale_x_f_.rows, d = scale_x_f_.cols;
  const float rate = first ? 1.0f : static_cast<float>(p_.learning_rate);
  const float keep = 1.0f - rate;
  if (first) {
    scale_num_ = cv::Mat::zeros(K, d, CV_32FC2);
    scale_den_ = cv::Mat::zeros(1, K, CV_32F);
  }
  float* den = scale_den_.ptr<float>();
  for (int k = 0; k < K; ++k) {
    // A = (1 - rate) A + rate * G conj(X), G a scalar per frequency.
    const float gr = rate * label_f[2 * k], gi = rate * label_f[2 * k + 1];
    const float* xp = scale_x_f_.ptr<float>(k);
    float* ap = scale_num_.ptr<float>(k);
    float energy = 0;
    for (int j = 0; j < d; ++j) {
      const float xr = xp[2 * j], xi = xp[2 * j + 1];
      ap[2 * j] = keep * ap[2 * j] + (gr * xr + gi * xi);
      ap[2 * j + 1] = keep * ap[2 * j + 1] + (gi * xr - gr * xi);
      energy += xr * xr + xi * xi;
    }
    den[k] = keep * den[k] + rate * energy;
  }
}

void Dsst::check_frame(const cv::Mat& frame, const char* who) const {
  if (frame.empty() || frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3))
    throw std::invalid_argument(std::string(who) + ": frame must be a non-empty CV_8UC1 or CV_8UC3 image");
  if (initialized_ && (frame.cols != frame_size_.width || frame.rows != frame_size_.height))
    throw std::invalid_argument(std::string(who) + ": frame size differs from the one the track started on");
}

void Dsst::learn(const cv::Mat& frame) {
  if (!initialized_) throw std::logic_error("Dsst::learn before init");
  check_frame(frame, "Dsst::learn");
  // The mean PSR of the frames learnt (an exponential average over about 10), the wide search's standard; here,
  // not in track(): the first track() after init, on the frame the filter was learnt from, gives PSR in the
  // hundreds.
  if (have_detection_ && psr_ >= p_.wide_search_psr) good_psr_ = good_psr_ > 0 ? 0.9 * good_psr_ + 0.1 * psr_ : psr_;
  if (p_.reuse_detection_samples && have_detection_) {
    // The target sits at the estimate inside the detection samples: labels centred there.
    learn_translation(detection_sample_, false);
    if (colour_) learn_colour(detection_sample_, false);
    learn_scale(false, detection_scale_index_);
  } else {
    const Sample t = translation_features(frame, pos_, scale_);
    learn_translation(t, false);
    if (colour_) learn_colour(t, false);
    scale_features(frame, pos_, scale_);
    learn_scale(false, label_no_change_);
  }
  have_detection_ = false;
}

// The filter's response to the sample whose DFTs are in feats_f_, y = IDFT(Σ_l A_l Z_l / (B + λ)), into resp_:
// its peak and PSR.
Dsst::Response Dsst::filter_response() {
  const float lambda = static_cast<float>(p_.lambda);
  const int n = cells_.area();
  resp_f_.create(cells_, CV_32FC2);
  resp_f_.setTo(0);
  float* rp = resp_f_.ptr<float>();
  for (int l = 0; l < kTranslationChannels; ++l) {
    const float* ap = num_[static_cast<size_t>(l)].ptr<float>();
    const float* zp = feats_f_[static_cast<size_t>(l)].ptr<float>();
    for (int i = 0; i < n; ++i) {
      rp[2 * i] += ap[2 * i] * zp[2 * i] - ap[2 * i + 1] * zp[2 * i + 1];
      rp[2 * i + 1] += ap[2 * i] * zp[2 * i + 1] + ap[2 * i + 1] * zp[2 * i];
    }
  }
  const float* dp = den_.ptr<float>();
  for (int i = 0; i < n; ++i) {
    const float inv = 1.0f / (dp[i] + lambda);
    rp[2 * i] *= inv;
    rp[2 * i + 1] *= inv;
  }
  cv::dft(resp_f_, resp_, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);

  cv::Point peak;
  double peak_value = 0;
  cv::minMaxLoc(resp_, nullptr, &peak_value, nullptr, &peak);
  const int W = cells_.width, H = cells_.height;

  // PSR = (peak - mean) / std over the response outside a square around the peak (wrapping).
  double sum = 0, sum2 = 0;
  int count = 0;
  const int k = p_.psr_exclude_cells;
  for (int y = 0; y < H; ++y) {
    const int dy = std::min(std::abs(y - peak.y), H - std::abs(y - peak.y));
    const float* row = resp_.ptr<float>(y);
    for (int x = 0; x < W; ++x) {
      const int dx = std::min(std::abs(x - peak.x), W - std::abs(x - peak.x));
      if (dx <= k && dy <= k) continue;
      sum += row[x];
      sum2 += static_cast<double>(row[x]) * row[x];
      ++count;
    }
  }
  double psr = 0.0;
  if (count > 1) {
    const double mean = sum / count;
    const double sd = std::sqrt(std::max(sum2 / count - mean * mean, 0.0));
    psr = std::max(0.0, (peak_value - mean) / std::max(sd, 1e-9));
  }
  return Response{peak, peak_value, psr};
}

// The translation step on a sample centred at centre: the filter's response (merged with the colour model's),
// its peak refined to a fraction of a cell, the filter's PSR. The sample's DFTs stay in feats_f_ (learn()).
Dsst::Translation Dsst::translate(const cv::Mat& frame, cv::Point2d centre) {
  const int cell = p_.cell_size;
  const Sample s = translation_features(frame, centre, scale_);
  const Response r = filter_response();
  const cv::Point peak = r.peak;
  const double peak_value = r.peak_value;
  const int W = cells_.width, H = cells_.height;
  auto at = [&](int y, int x) { return static_cast<double>(resp_.at<float>((y + H) % H, (x + W) % W)); };
  const double px = peak.x + peak_offset(at(peak.y, peak.x - 1), peak_value, at(peak.y, peak.x + 1));
  const double py = peak.y + peak_offset(at(peak.y - 1, peak.x), peak_value, at(peak.y + 1, peak.x));
  double qx = px, qy = py;
  if (colour_) {
    // Staple's merge; the position is the merged response's peak, the confidence (PSR) stays the filter's.
    colour_response(s);
    const float a = static_cast<float>(p_.colour_weight);
    cv::addWeighted(resp_, 1.0f - a, colour_resp_, a, 0.0, merged_);
    cv::Point m;
    double mv = 0;
    cv::minMaxLoc(merged_, nullptr, &mv, nullptr, &m);
    auto mat = [&](int y, int x) { return static_cast<double>(merged_.at<float>((y + H) % H, (x + W) % W)); };
    qx = m.x + peak_offset(mat(m.y, m.x - 1), mv, mat(m.y, m.x + 1));
    qy = m.y + peak_offset(mat(m.y - 1, m.x), mv, mat(m.y + 1, m.x));
  }
  return Translation{s, s.centre.x + (qx + 0.5) * cell * s.frame_per_model.x, s.centre.y + (qy + 0.5) * cell * s.frame_per_model.y, r.psr};
}

DsstEstimate Dsst::track(const cv::Mat& frame, bool wide_search) {
  if (!initialized_) throw std::logic_error("Dsst::track before init");
  check_frame(frame, "Dsst::track");
  const float lambda = static_cast<float>(p_.lambda);

  Translation t = translate(frame, pos_);
  if (wide_search && p_.wide_search_psr > 0 && t.psr < p_.wide_search_psr) {
    // A weak response: the target may have jumped out of the window (a fast pan: uav123_person12_1 moves 27 px a
    // frame, two thirds of its width). The 8 windows around, wide_search_offset of a window apart; the best is
    // taken only if it is a sure frame itself (PSR >= wide_search_accept_psr), else the weak estimate stands.
    const cv::Size2d w = window_frame_ * scale_;
    const double off = p_.wide_search_offset;
    std::optional<cv::Point2d> best_centre;
    // A sure frame by this track's own standard too: a still cut to another scene gave windows at PSR 10+
    // (the sample clip's track runs at 36..60).
    double best_psr = std::max({p_.wide_search_psr, p_.wide_search_accept_psr, p_.wide_search_accept_share * good_psr_});
    // The window's own sample is kept aside (learn() reads it when no other window is taken). The 8 windows are
    // cut from one sample of the area they cover (its features computed once: 4 windows' area, not 8), each
    // offset by a whole number of cells, and judged by the filter's PSR alone (no colour score).
    std::swap(feats_f_, kept_feats_f_);
    const int cell = p_.cell_size;
    const int ox = std::max(1, static_cast<int>(std::lround(off * cells_.width)));
    const int oy = std::max(1, static_cast<int>(std::lround(off * cells_.height)));
    const cv::Size around(cells_.width + 2 * ox, cells_.height + 2 * oy);
    const auto [origin, fpm] = crop_resized(frame, pos_, cv::Size2d(w.width * around.width / cells_.width, w.height * around.height / cells_.height),
                                            around * cell, crop_, shrunk_, around_patch_);
    patch_features(around_patch_, around, around_feats_);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const cv::Rect window((1 + dx) * ox, (1 + dy) * oy, cells_.width, cells_.height);
        const cv::Point2d c(origin.x + (window.x + cells_.width / 2.0) * cell * fpm.x,
                            origin.y + (window.y + cells_.height / 2.0) * cell * fpm.y);
        if ((dx == 0 && dy == 0) || c.x < 0 || c.y < 0 || c.x >= frame.cols || c.y >= frame.rows) continue;
        window_spectra(around_feats_, window);
        const double psr = filter_response().psr;
        if (psr >= best_psr) {
          best_psr = psr;
          best_centre = c;
        }
      }
    if (best_centre) {
      // Sampled again where it was found, with its colour score: its features (and patch) are the ones learnt from.
      t = translate(frame, *best_centre);
    } else {
      std::swap(feats_f_, kept_feats_f_);
    }
  }
  const Sample& s = t.sample;
  psr_ = t.psr;
  pos_.x = std::clamp(t.x, 0.0, frame.cols - 1e-3);
  pos_.y = std::clamp(t.y, 0.0, frame.rows - 1e-3);

  // Scale: the same filter in 1-D over the scale samples at the new position.
  scale_features(frame, pos_, scale_);
  const int S = static_cast<int>(scale_factors_.size());
  scale_resp_f_.create(1, S, CV_32FC2);
  float* sp = scale_resp_f_.ptr<float>();
  const float* sd = scale_den_.ptr<float>();
  for (int k = 0; k < scale_x_f_.rows; ++k) {
    const float* ap = scale_num_.ptr<float>(k);
    const float* zp = scale_x_f_.ptr<float>(k);
    float yr = 0, yi = 0;
    for (int j = 0; j < scale_x_f_.cols; ++j) {
      yr += ap[2 * j] * zp[2 * j] - ap[2 * j + 1] * zp[2 * j + 1];
      yi += ap[2 * j] * zp[2 * j + 1] + ap[2 * j + 1] * zp[2 * j];
    }
    const float inv = 1.0f / (sd[k] + lambda);
    sp[2 * k] = yr * inv;
    sp[2 * k + 1] = yi * inv;
  }
  for (int k = scale_x_f_.rows; k < S; ++k) {  // the conjugates of the stored half (scale_spectrum)
    sp[2 * k] = sp[2 * (S - k)];
    sp[2 * k + 1] = -sp[2 * (S - k) + 1];
  }
  double change = 0;  // in scale steps
  if (scale_interp_) {
    // fDSST: the spectrum zero-padded to number_of_scales (its low ceil(n/2) and high floor((n-1)/2)
    // coefficients; the Nyquist term of an even n dropped, which keeps it Hermitian), the real response at
    // every interpolated scale.
    const int Si = p_.number_of_scales;
    scale_interp_f_.create(1, Si, CV_32FC2);
    scale_interp_f_.setTo(0);
    float* ip = scale_interp_f_.ptr<float>();
    const int low = (S + 1) / 2, high = (S - 1) / 2;
    for (int i = 0; i < low; ++i) {
      ip[2 * i] = sp[2 * i];
      ip[2 * i + 1] = sp[2 * i + 1];
    }
    for (int i = 1; i <= high; ++i) {
      ip[2 * (Si - i)] = sp[2 * (S - i)];
      ip[2 * (Si - i) + 1] = sp[2 * (S - i) + 1];
    }
    cv::dft(scale_interp_f_, scale_resp_, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_ROWS | cv::DFT_REAL_OUTPUT);
    cv::Point best;
    cv::minMaxLoc(scale_resp_, nullptr, nullptr, nullptr, &best);
    change = interp_exp_[static_cast<size_t>(best.x)];
  } else {
    cv::dft(scale_resp_f_, scale_resp_, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_ROWS | cv::DFT_REAL_OUTPUT);
    cv::Point best;
    cv::minMaxLoc(scale_resp_, nullptr, nullptr, nullptr, &best);
    change = best.x - (S - 1) / 2;
  }
  const double new_scale = std::clamp(scale_ * std::pow(p_.scale_step, change), min_scale_, max_scale_);
  // The label index whose change is nearest the clamped one is where the target's size sits in the sample.
  const int Si = p_.number_of_scales;
  const int steps = std::clamp(static_cast<int>(std::lround(std::log(new_scale / scale_) / std::log(p_.scale_step))),
                               -((Si - 1) / 2), Si / 2);
  detection_scale_index_ = scale_interp_ ? (steps + Si) % Si : std::clamp(steps + (S - 1) / 2, 0, S - 1);
  scale_ = new_scale;
  detection_sample_ = s;
  have_detection_ = true;
  return estimate();
}

}  // namespace gpilot
