// Whether a frame carries colour at all. A monochrome or infrared camera, or a greyscale video, has no skin
// colour in it: every pixel is grey, so the skin model sees no hand in any frame, whatever the user does. The
// stage says so (a counted rejection naming the cause) instead of reporting "no hand" frame after frame.
#pragma once

#include <opencv2/core.hpp>

#include "hands/hands_params.hpp"

namespace gpilot {

// Fraction of sampled pixels (every 4th in x and y) whose max(B,G,R) - min(B,G,R) is at least min_chroma, counted
// until `enough` of them are found (then a lower bound). bgr: CV_8UC3.
double coloured_fraction(const cv::Mat& bgr, int min_chroma, double enough = 1.0);

// The frame has colour: at least skin.min_colour_fraction of its sampled pixels have skin.min_chroma.
bool has_colour(const cv::Mat& bgr, const SkinParams& skin);

}  // namespace gpilot
