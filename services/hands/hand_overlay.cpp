#include "hand_overlay.hpp"

#include <opencv2/imgproc.hpp>

namespace gpilot {

void draw_hand_overlay(cv::Mat& img, const HandResult& r, const cv::Mat& skin_mask, const cv::Rect& roi) {
  CV_Assert(img.type() == CV_8UC3);
  const HandGeometry& g = r.geometry;
  if (!skin_mask.empty() && roi.size() == skin_mask.size() && (roi & cv::Rect(0, 0, img.cols, img.rows)) == roi)
    img(roi).setTo(cv::Scalar(0, 0, 255), skin_mask);
  if (!g.valid) return;
  const cv::Scalar grey(160, 160, 160), green(0, 200, 0), yellow(0, 230, 255), cyan(255, 255, 0), dark(60, 60, 60);
  cv::rectangle(img, g.roi, grey, 1);
  cv::rectangle(img, g.box, green, 2);
  cv::line(img, {g.box.x, g.face_rows_end}, {g.box.br().x, g.face_rows_end}, dark, 1);
  cv::line(img, {g.box.x, g.legs_rows_begin}, {g.box.br().x, g.legs_rows_begin}, dark, 1);
  cv::drawMarker(img, g.shoulder_centre, cyan, cv::MARKER_CROSS, 12, 2);
  cv::drawMarker(img, g.body_centre, cyan, cv::MARKER_TILTED_CROSS, 10, 2);
  if (r.kind == HandKind::None) return;
  cv::rectangle(img, r.hand_box, yellow, 2);
  const cv::Point2f from = r.kind == HandKind::Out ? g.shoulder_centre : g.body_centre;
  cv::arrowedLine(img, from, from + r.vector, yellow, 2, cv::LINE_AA, 0, 0.08);
}

}  // namespace gpilot
