// A textured scene moved and scaled by known amounts: the known answers of the DSST tests.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace gpilot::test {

// Smooth random texture (fixed seed), BGR, so that every patch has gradients in all directions.
inline cv::Mat texture(cv::Size size, int seed) {
  cv::RNG rng(static_cast<uint64_t>(seed));
  cv::Mat noise(size, CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::Mat out;
  cv::GaussianBlur(noise, out, cv::Size(0, 0), 2.5);
  cv::normalize(out, out, 0, 255, cv::NORM_MINMAX);
  return out;
}

// The frame in which the texture point `anchor` appears at `centre`, the texture magnified by `scale`.
inline cv::Mat view(const cv::Mat& tex, cv::Point2d anchor, cv::Point2d centre, double scale, cv::Size frame) {
  // frame x = centre + scale * (tex x - anchor), in continuous coordinates (pixel i covers [i, i+1)).
  const cv::Matx23d m(scale, 0, centre.x - scale * anchor.x + 0.5 * scale - 0.5,  //
                      0, scale, centre.y - scale * anchor.y + 0.5 * scale - 0.5);
  cv::Mat out;
  cv::warpAffine(tex, out, m, frame, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

}  // namespace gpilot::test
