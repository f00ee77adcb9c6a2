// Draws a hand result onto a frame for people to look at: skin in red (as the paper's figure), the search
// rectangle, the removed face/neck and legs bands, the user box, p_uc and p_bc, the hand square and the vector.
#pragma once

#include <opencv2/core.hpp>

#include "hands/hand_detector.hpp"

namespace gpilot {

// img: CV_8UC3, drawn on in place. skin_mask: 0/1 over roi (HandDetector::last_mask/last_roi), may be empty.
void draw_hand_overlay(cv::Mat& img, const HandResult& result, const cv::Mat& skin_mask, const cv::Rect& roi);

}  // namespace gpilot
