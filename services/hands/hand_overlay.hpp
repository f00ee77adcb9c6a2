// Draws a hands observation onto a frame for people to look at: the user box, p_uc and p_bc, the hand square and
// the vector; with the skin method's part, skin in red (as the paper's figure), the search rectangle and the
// removed face/neck and legs bands.
#pragma once

#include <opencv2/core.hpp>

#include "hands/hand_method.hpp"

namespace gpilot {

// img: CV_8UC3, drawn on in place.
void draw_hand_overlay(cv::Mat& img, const HandsOutput& result);

}  // namespace gpilot
