#include "truth_overlay.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace gpilot {

namespace {

cv::Scalar colour(ArmTruth t) {
  switch (t) {
    case ArmTruth::Out: return {0, 140, 255};
    case ArmTruth::FrontHigh: return {255, 120, 0};
    case ArmTruth::FrontLow: return {255, 200, 80};
    case ArmTruth::Rest: return {0, 200, 0};
    case ArmTruth::Ambiguous: return {150, 150, 150};
  }
  return {255, 255, 255};
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, const cv::Scalar& c) {
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, c, 1, cv::LINE_AA);
}

}  // namespace

void draw_keypoint_truth(cv::Mat& img, const PersonKeypointTruth& t, const cv::Rect2f& person_box,
                         const std::optional<cv::Rect2f>& face, const std::string& caption) {
  CV_Assert(img.type() == CV_8UC3);
  cv::rectangle(img, cv::Rect(person_box), cv::Scalar(255, 255, 255), 1);
  if (face) cv::rectangle(img, cv::Rect(*face), cv::Scalar(255, 0, 255), 2);
  if (t.usable) {
    if (t.face_box) cv::rectangle(img, cv::Rect(*t.face_box), cv::Scalar(200, 200, 200), 1);
    cv::drawMarker(img, t.torso_centre, cv::Scalar(255, 255, 255), cv::MARKER_DIAMOND, 8, 1);
    for (const auto& [side, arm] : {std::pair<const char*, const ArmKeypointTruth*>{"L", &t.left}, {"R", &t.right}}) {
      const cv::Scalar c = colour(arm->label);
      cv::line(img, arm->shoulder, arm->elbow, c, 2, cv::LINE_AA);
      cv::line(img, arm->elbow, arm->wrist, c, 2, cv::LINE_AA);
      cv::circle(img, arm->wrist, 4, c, -1, cv::LINE_AA);
      text(img, std::string(side) + " " + arm_truth_name(arm->label), cv::Point(arm->wrist) + cv::Point(6, -6), 0.45, c);
    }
  }
  int y = 18;
  for (size_t begin = 0; begin <= caption.size();) {
    const size_t end = std::min(caption.find('\n', begin), caption.size());
    text(img, caption.substr(begin, end - begin), {6, y}, 0.45, cv::Scalar(255, 255, 255));
    y += 18;
    begin = end + 1;
  }
}

}  // namespace gpilot
