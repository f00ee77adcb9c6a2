// Haar face search and head-body ratio (see face_detector.hpp).
#include "face_detector.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "paths.hpp"

namespace gpilot {

cv::Rect2d body_from_face(const cv::Rect2d& face, const TrackerParams& p) { return body_from_face(face, p.body()); }

cv::Rect face_recheck_window(const cv::Rect2d& b, const TrackerParams& p) {
  const double fw = b.width / p.body_width_in_faces, fh = b.height / p.body_height_in_faces;
  const double face_top = b.y + p.body_top_in_faces * fh;
  return cv::Rect(cv::Rect2d(b.x + b.width / 2 - 1.5 * fw, face_top - 0.75 * fh, 3 * fw, 2.5 * fh));
}

FaceDetector::FaceDetector(const TrackerParams& params) : p_(params) {
  const std::string path = resolve_project_path(p_.face.cascade);
  if (!cascade_.load(path))
    throw std::runtime_error("face cascade '" + path + "' is missing or not a cascade (package opencv-data)");
}

std::optional<FaceDetection> FaceDetector::detect(const cv::Mat& frame) {
  if (frame.empty()) return std::nullopt;
  if (frame.channels() == 3)
    cv::cvtColor(frame, grey_, cv::COLOR_BGR2GRAY);
  else
    frame.copyTo(grey_);
  // The budget: at least face.downscale, and shrunk to at most max_search_pixels.
  const double k = std::max({1.0, p_.face.downscale,
                             std::sqrt(static_cast<double>(grey_.total()) / std::max(1.0, p_.face.max_search_pixels))});
  const cv::Mat* img = &grey_;
  if (k > 1.0) {
    cv::resize(grey_, small_, cv::Size(), 1.0 / k, 1.0 / k, cv::INTER_AREA);
    img = &small_;
  }
  // No histogram equalisation: on messi5.jpg it turns the shirt into a face at min_neighbors 5.
  std::vector<cv::Rect> faces;
  const int min_px = p_.face.min_face_px;
  cascade_.detectMultiScale(*img, faces, p_.face.scale_factor, p_.face.min_neighbors, 0, cv::Size(min_px, min_px));
  if (faces.empty()) return std::nullopt;
  // The largest face, ties broken by position so that the choice does not depend on detection order.
  const auto best = std::max_element(faces.begin(), faces.end(), [](const cv::Rect& a, const cv::Rect& b) {
    if (a.area() != b.area()) return a.area() < b.area();
    return std::make_pair(a.y, a.x) > std::make_pair(b.y, b.x);
  });
  FaceDetection d;
  d.face = cv::Rect2d(best->x * k, best->y * k, best->width * k, best->height * k);
  d.body = body_from_face(d.face, p_) & cv::Rect2d(0, 0, frame.cols, frame.rows);
  return d;
}

std::optional<FaceDetection> FaceDetector::detect(const cv::Mat& frame, const cv::Rect& roi) {
  const cv::Rect r = roi & cv::Rect(0, 0, frame.cols, frame.rows);
  if (r.width < p_.face.min_face_px || r.height < p_.face.min_face_px) return std::nullopt;
  auto d = detect(frame(r));
  if (!d) return std::nullopt;
  d->face += cv::Point2d(r.tl());
  d->body = body_from_face(d->face, p_) & cv::Rect2d(0, 0, frame.cols, frame.rows);
  return d;
}

}  // namespace gpilot
