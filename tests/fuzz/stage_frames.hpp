// Small frames for the stage-core fuzz targets, made from a few input bytes: flat colour with noise, a
// checkerboard, or a crop of a real photo with a face (so the face search and the skin model have something
// real to find), at the size the input asks for.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "fuzz_input.hpp"
#include "paths.hpp"

namespace gpilot::fuzz {

inline const cv::Mat& photo() {
  static const cv::Mat img = [] {
    cv::Mat m = cv::imread(resolve_project_path("data/people/astronaut.png"), cv::IMREAD_COLOR);
    if (m.empty()) fail("data/people/astronaut.png does not load");
    cv::resize(m, m, cv::Size(128, 128), 0, 0, cv::INTER_AREA);
    return m;
  }();
  return img;
}

// A CV_8UC3 frame, sides in [min_side, max_side].
inline cv::Mat frame(Input& in, int min_side, int max_side) {
  const int w = static_cast<int>(in.in(min_side, max_side)), h = static_cast<int>(in.in(min_side, max_side));
  const uint8_t kind = in.byte() % 3;
  cv::Mat f(h, w, CV_8UC3);
  if (kind == 0) {
    const cv::Vec3b base(in.byte(), in.byte(), in.byte());
    const uint8_t noise = in.byte();
    cv::RNG rng(in.raw<uint32_t>());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        cv::Vec3b& p = f.at<cv::Vec3b>(y, x);
        for (int c = 0; c < 3; ++c) p[c] = cv::saturate_cast<uint8_t>(base[c] + (noise ? rng.uniform(-noise, noise + 1) : 0));
      }
  } else if (kind == 1) {
    const cv::Vec3b a(in.byte(), in.byte(), in.byte()), b(in.byte(), in.byte(), in.byte());
    const int cell = 1 + in.byte() % 16;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) f.at<cv::Vec3b>(y, x) = ((x / cell + y / cell) & 1) ? a : b;
  } else {
    // A crop of the photo: scale (crop side 16..128) and offset from the input, resized to the frame.
    const int side = static_cast<int>(in.in(16, 128));
    const int x0 = static_cast<int>(in.in(0, 128 - side)), y0 = static_cast<int>(in.in(0, 128 - side));
    cv::resize(photo()(cv::Rect(x0, y0, side, side)), f, f.size(), 0, 0, cv::INTER_LINEAR);
  }
  return f;
}

}  // namespace gpilot::fuzz
