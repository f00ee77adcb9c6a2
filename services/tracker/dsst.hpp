// DSST, the Discriminative Scale Space Tracker (Danelljan, Häger, Khan, Felsberg, BMVC 2014), our own
// implementation: a multi-channel correlation filter for translation on 31 FHOG channels (4x4 cells) plus
// grey intensity, then a separate 1-D filter over 33 scales on the FHOG of resized patches (not
// compressed: d = 31 x cells of the scale model, as in the BMVC paper, not fDSST's PCA; optionally fDSST's
// fewer sampled scales, the response interpolated to 33 in the Fourier domain). Both filters are
//   A_l = (1-η) A_l + η G conj(F_l),   B = (1-η) B + η Σ_l |F_l|²,   y = IDFT(Σ_l A_l Z_l / (B + λ))
// with every transform a real-to-complex cv::dft into buffers kept between frames.
// No clock, no I/O: frames in, boxes out; the same frames give the same boxes.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "fhog.hpp"
#include "tracker_params.hpp"

namespace gpilot {

struct DsstEstimate {
  cv::Rect2d box;       //!< x, y (top-left), width, height, pixels
  double psr = 0.0;     //!< peak-to-sidelobe ratio of the translation response
  double scale = 1.0;   //!< size relative to the initial box
};

class Dsst {
 public:
  explicit Dsst(const DsstParams& params);

  // Starts a track on box (pixels, at least 2x2, centre inside the frame). frame: CV_8UC3 or CV_8UC1.
  // Throws std::invalid_argument for an empty frame or a box it cannot track.
  void init(const cv::Mat& frame, const cv::Rect2d& box);

  // Finds the target in frame: translation, then scale at the new position. The model is not changed.
  // wide_search: a weak response is searched again around (params wide_search_psr); false: the one window.
  DsstEstimate track(const cv::Mat& frame, bool wide_search = true);
  // Updates both filters with samples of frame at the current estimate (rate η).
  void learn(const cv::Mat& frame);
  // The published tracker: track, then learn, every frame.
  DsstEstimate update(const cv::Mat& frame) {
    const DsstEstimate e = track(frame);
    learn(frame);
    return e;
  }

  bool initialized() const { return initialized_; }
  DsstEstimate estimate() const;
  // Puts the target back where an earlier estimate() had it (position and scale; the model is unchanged):
  // the next track() searches around there. Throws std::logic_error before init.
  void restore(const DsstEstimate& e);
  const DsstParams& params() const { return p_; }

 private:
  // A crop of the frame resized to the model window: where its centre is and how many frame pixels one
  // model pixel spans (they differ from the asked ones by the rounding of the crop to whole pixels).
  struct Sample {
    cv::Point2d centre;
    cv::Point2d frame_per_model;
  };
  struct Translation {
    Sample sample;
    double x, y;  //!< the estimate, frame pixels
    double psr;
  };
  struct Response {
    cv::Point peak;  //!< cell of the response's maximum
    double peak_value;
    double psr;
  };
  Translation translate(const cv::Mat& frame, cv::Point2d centre);
  Response filter_response();
  Sample translation_features(const cv::Mat& frame, cv::Point2d pos, double scale);
  // The 32 translation channels (FHOG + grey) of a model-resolution patch of cells (at cell_size each) into out.
  void patch_features(const cv::Mat& patch, cv::Size cells, std::vector<cv::Mat>& out);
  // The cosine-windowed DFTs of one window (cells_ in size) of features into feats_f_ (feats_: the windowed maps).
  void window_spectra(const std::vector<cv::Mat>& features, const cv::Rect& window);
  void scale_features(const cv::Mat& frame, cv::Point2d pos, double scale);
  void scale_spectrum();  //!< scale_x_ into scale_x_f_
  void learn_translation(const Sample& s, bool first);
  void learn_scale(bool first, int label_centre);
  void gaussian_label(cv::Point2d centre_cells);
  void check_frame(const cv::Mat& frame, const char* who) const;
  // Staple's colour model on the translation sample in patch_ (BGR): learn the foreground / background
  // histograms at the current estimate, or score every cell of the window.
  void learn_colour(const Sample& s, bool first);
  void colour_response(const Sample& s);
  cv::Rect2d target_in_patch(const Sample& s) const;

  DsstParams p_;
  bool initialized_ = false;
  Fhog fhog_;

  // Track state.
  cv::Size frame_size_;
  cv::Point2d pos_;          // target centre, frame pixels
  cv::Size2d base_size_;     // target size at scale 1, frame pixels
  double scale_ = 1.0;
  double min_scale_ = 0.0, max_scale_ = 0.0;
  double psr_ = 0.0;
  double good_psr_ = 0.0;    // mean PSR of the frames learnt at wide_search_psr or more (exponential, rate 0.1)

  // Translation model: the window (target × (1 + padding)) at model resolution.
  double model_factor_ = 1.0;  // model pixels per frame pixel at scale 1
  cv::Size cells_;             // window in cells (DFT size)
  cv::Size2d window_frame_;    // window in frame pixels at scale 1
  double sigma_cells_ = 1.0;
  cv::Mat cos_window_;         // CV_32F, cells_
  std::vector<cv::Mat> num_;   // A_l, CV_32FC2
  cv::Mat den_;                // B, CV_32F
  cv::Mat label_, label_f_;    // G in space (CV_32F) and its DFT (CV_32FC2)

  // Scale model. The BMVC filter samples every one of number_of_scales scales; fDSST's (scale_samples) samples
  // fewer and interpolates the response: sampled scale k is a^e_k, e_k = (k - (n-1)/2) S / n (a = scale_step),
  // the label peaks at response index 0 for "no change" (fDSST's circular shift), and the interpolated
  // response's index m is a change of a^interp_exp_[m].
  bool scale_interp_ = false;
  int label_no_change_ = 0;        //!< the scale label index of "the size did not change"
  std::vector<int> interp_exp_;    //!< fDSST: per interpolated index, the change in scale steps
  std::vector<double> scale_factors_;
  std::vector<float> scale_window_;
  cv::Size scale_model_sz_;
  std::vector<cv::Mat> scale_labels_f_;  // per peak (BMVC: sample index; fDSST: interpolated index): 1 x n, CV_32FC2
  // The samples of the last track() (translation DFTs in feats_f_, scale DFTs in scale_x_f_), kept for
  // learn() when params reuse_detection_samples.
  bool have_detection_ = false;
  Sample detection_sample_;
  int detection_scale_index_ = 0;
  cv::Mat scale_num_;          // (S/2 + 1) x d, CV_32FC2: frequency k of every feature (scale_spectrum)
  cv::Mat scale_den_;          // 1 x (S/2 + 1), CV_32F
  std::vector<float> scale_twiddles_;  // e^(-2 pi i k s / S), k = 0..S/2, s = 0..S-1: (cos, sin) pairs

  // Buffers reused every frame.
  cv::Mat crop_, shrunk_, patch_, grey_, grey_cells_, scale_inter_, scale_patch_;
  std::vector<cv::Mat> feats_;      // 32 channels, CV_32F
  std::vector<cv::Mat> feats_f_;    // their DFTs, CV_32FC2
  std::vector<cv::Mat> kept_feats_f_;  // the wide search: the window's own sample's DFTs, kept aside
  cv::Mat around_patch_;               // the wide search: the sample of the 8 windows' area, and its features
  std::vector<cv::Mat> around_feats_;
  std::vector<cv::Mat> scale_fhog_;
  cv::Mat scale_x_, scale_x_f_;     // S x d real (a sample a row), (S/2 + 1) x d complex
  std::vector<float> dft_re_, dft_im_;
  cv::Mat resp_f_, resp_, scale_resp_f_, scale_resp_, scale_interp_f_;
  // Colour model (colour_weight > 0 and colour frames): 32x32x32-bin BGR histograms, each summing to 1.
  bool colour_ = false;
  std::vector<float> fg_hist_, bg_hist_;
  // One frame's counts of a histogram's bins, all zero between frames: the bins counted are listed, so that the
  // blend and the clear touch those alone.
  struct BinCounts {
    std::vector<float> n;
    std::vector<int> counted;
    double total = 0;
    void add(int bin);
    void blend_into(std::vector<float>& hist, float rate) const;
    void clear();
  };
  BinCounts fg_counts_, bg_counts_;
  cv::Mat likelihood_, colour_cells_, colour_resp_, merged_;
};

}  // namespace gpilot
