// FHOG: the 31-channel histogram of oriented gradients of Felzenszwalb et al. (PAMI 2010), as used by
// DSST, KCF and dlib: 18 contrast-sensitive + 9 contrast-insensitive orientation channels, each normalised
// by the 4 surrounding 2x2-cell blocks and truncated at 0.2, plus 4 gradient-energy channels. Our own code
// (OpenCV exports no FHOG). Buffers are kept between calls: no allocation once the sizes are stable.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace gpilot {

class Fhog {
 public:
  static constexpr int kChannels = 31;

  // Builds the process's orientation table (about 5 ms, once) if no Fhog has: a tracker's first frame does not
  // wait for it.
  Fhog();

  // patch: CV_8UC1 or CV_8UC3 (the gradient of the strongest colour channel is used, as Felzenszwalb).
  // out[first .. first+30] get CV_32F maps of floor(rows/cell) x floor(cols/cell) cells (out grows if
  // needed); cell centres sit at (i + 0.5) * cell pixels. Border cells use the nearest blocks in the map.
  void compute(const cv::Mat& patch, int cell, std::vector<cv::Mat>& out, size_t first = 0);

 private:
  cv::Mat hist_;  // rows x cols x 18 orientation histogram, CV_32F rows*cols x 18
  cv::Mat norm_;  // per-cell energy of the 9 contrast-insensitive bins, CV_32F
  cv::Mat block_norm_;  // per 2x2-cell block: 1 / sqrt(its energy + eps), CV_32F
  std::vector<int> gdx_, gdy_, gv_;  // one row's strongest gradient and its squared magnitude
  std::vector<int> xcell_;   // per patch column: left cell of its bilinear pair
  std::vector<float> xw_;    // per patch column: weight of the right cell
};

}  // namespace gpilot
