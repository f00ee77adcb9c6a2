// Draws the keypoint truth of one person for people to look at: the person's box (white), the Haar face used
// (magenta), the keypoint face box (thin grey), each arm as lines shoulder-elbow-wrist in its label's colour
// with the label at the wrist (OUT orange, FRONT_HIGH/LOW blue, REST green, AMBIGUOUS grey).
#pragma once

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "keypoint_truth.hpp"

namespace gpilot {

// img: CV_8UC3, drawn on in place. caption: text at the top left ('\n' starts a new line).
void draw_keypoint_truth(cv::Mat& img, const PersonKeypointTruth& truth, const cv::Rect2f& person_box,
                         const std::optional<cv::Rect2f>& face, const std::string& caption);

}  // namespace gpilot
