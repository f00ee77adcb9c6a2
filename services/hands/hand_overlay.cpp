#include "hand_overlay.hpp"

#include <opencv2/imgproc.hpp>

namespace gpilot {

void draw_hand_overlay(cv::Mat& img, const HandsOutput& r) {
  CV_Assert(img.type() == CV_8UC3);
  const cv::Scalar grey(160, 160, 160), green(0, 200, 0), yellow(0, 230, 255), cyan(255, 255, 0), dark(60, 60, 60);
  if (r.skin) {
    const SkinDiagnostics& s = *r.skin;
    if (!s.mask.empty() && s.roi.size() == s.mask.size() && (s.roi & cv::Rect(0, 0, img.cols, img.rows)) == s.roi)
      img(s.roi).setTo(cv::Scalar(0, 0, 255), s.mask);
    const HandGeometry& g = s.detection.geometry;
    if (!g.valid) return;
    cv::rectangle(img, g.roi, grey, 1);
    cv::line(img, {g.box.x, g.face_rows_end}, {g.box.br().x, g.face_rows_end}, dark, 1);
    cv::line(img, {g.box.x, g.legs_rows_begin}, {g.box.br().x, g.legs_rows_begin}, dark, 1);
  }
  cv::rectangle(img, cv::Rect(r.user_box), green, 2);
  cv::drawMarker(img, r.shoulder_centre, cyan, cv::MARKER_CROSS, 12, 2);
  cv::drawMarker(img, r.body_centre, cyan, cv::MARKER_TILTED_CROSS, 10, 2);
  if (r.kind == HandKind::None) return;
  cv::rectangle(img, r.hand_box, yellow, 2);
  const cv::Point2f from = r.kind == HandKind::Out ? r.shoulder_centre : r.body_centre;
  cv::arrowedLine(img, from, from + r.vector, yellow, 2, cv::LINE_AA, 0, 0.08);
}

}  // namespace gpilot
