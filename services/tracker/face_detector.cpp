// Haar face search and head-body ratio (see face_detector.hpp).
#include "face_detector.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>


namespace gpilot {

// The face re-check's window around where the box puts the face, in face sizes (a face-and-a-half around it):
// the face is found where it has moved to since the box was placed, up to a face width either side and most of
// a face height up or down, while a face further off (a bystander's beside the user) stays outside.
constexpr double kRecheckWindowWidthInFaces = 3.0;    //!< centred on the expected face
constexpr double kRecheckWindowAboveInFaces = 0.75;   //!< from above the expected face's top
constexpr double kRecheckWindowHeightInFaces = 2.5;

cv::Rect face_recheck_window(const cv::Rect2d& b, const BodyProportions& r) {
  const cv::Rect2d f = face_from_body(b, r);
  const double either_side = (kRecheckWindowWidthInFaces - 1) / 2;  // face widths left and right of the face
  return cv::Rect(cv::Rect2d(f.x - either_side * f.width, f.y - kRecheckWindowAboveInFaces * f.height,
                             kRecheckWindowWidthInFaces * f.width, kRecheckWindowHeightInFaces * f.height));
}

cv::Rect face_recheck_window(const cv::Rect2d& b, const TrackerParams& p) { return face_recheck_window(b, p.body()); }

FaceDetector::FaceDetector(const TrackerParams& params, cv::CascadeClassifier cascade)
    : p_(params), cascade_(std::move(cascade)) {
  if (cascade_.empty()) throw std::invalid_argument("FaceDetector: the face cascade is empty (load_face_cascade)");
}

namespace {
// The enlarged search (face.upscale) looks for faces up to this much above min_face_px in the frame: the
// cascade's windows come in scale_factor steps, and a face just above min_face_px (the synthetic user's
// 20.8 px at 5 m) was found by neither search without the overlap.
constexpr double kUpscaleSizeOverlap = 1.25;

std::optional<FaceDetection> first(const std::vector<FaceDetection>& faces) {
  if (faces.empty()) return std::nullopt;
  return faces.front();
}
}  // namespace

std::optional<FaceDetection> FaceDetector::detect(const cv::Mat& frame, double min_face) { return first(detect_all(frame, min_face)); }
std::optional<FaceDetection> FaceDetector::detect(const cv::Mat& frame, const cv::Rect& roi, double min_face) {
  return first(detect_all(frame, roi, min_face));
}
std::optional<FaceDetection> FaceDetector::scan_step(const cv::Mat& frame) { return first(scan_step_all(frame)); }

std::vector<FaceDetection> FaceDetector::detect_all(const cv::Mat& frame, double min_face, double max_face) {
  return detect_all_at(frame, min_face, max_face, p_.face.scale_factor);
}

std::vector<FaceDetection> FaceDetector::detect_all_at(const cv::Mat& frame, double min_face, double max_face,
                                                       double scale_factor) {
  if (frame.empty()) return {};
  grey_of(frame);
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
  const int bound_px = max_face > 0 ? static_cast<int>(std::ceil(max_face / k)) : 0;  // in img; 0: none
  if (bound_px == 0 || bound_px >= min_px)
    cascade_.detectMultiScale(*img, faces, scale_factor, p_.face.min_neighbors, 0, cv::Size(min_px, min_px),
                              cv::Size(bound_px, bound_px));
  std::vector<FaceDetection> out = sorted_of(faces, k, cv::Point(), frame);
  // Faces below min_face_px, in an enlarged copy, when that copy is within the budget (a small window).
  const double u = p_.face.upscale;
  int max_px = static_cast<int>(std::ceil(kUpscaleSizeOverlap * min_px * u));
  if (max_face > 0) max_px = std::min(max_px, static_cast<int>(std::ceil(max_face * u)));
  // The smallest face wanted, in the enlarged copy (the cascade's cost is mostly its smallest windows).
  const int from_px = std::max(min_px, static_cast<int>(std::floor(min_face * u)));
  if (u > 1.0 && k <= 1.0 && from_px <= max_px && static_cast<double>(grey_.total()) * u * u <= p_.face.max_search_pixels) {
    const size_t first = out.size();
    for (const FaceDetection& d : search_enlarged(u, from_px, max_px, frame, scale_factor)) {
      bool seen = false;  // a face of the sizes both searches cover, found by the first
      for (size_t i = 0; i < first; ++i)
        seen = seen || (d.face & out[i].face).area() > 0.5 * std::min(d.face.area(), out[i].face.area());
      if (!seen) out.push_back(d);
    }
  }
  return out;
}

std::vector<FaceDetection> FaceDetector::sorted_of(std::vector<cv::Rect> faces, double k, cv::Point offset,
                                                   const cv::Mat& frame) const {
  // The largest face first, ties broken by position so that the order does not depend on detection order.
  std::sort(faces.begin(), faces.end(), [](const cv::Rect& a, const cv::Rect& b) {
    if (a.area() != b.area()) return a.area() > b.area();
    return std::make_pair(a.y, a.x) < std::make_pair(b.y, b.x);
  });
  std::vector<FaceDetection> out;
  for (const cv::Rect& f : faces) {
    FaceDetection d;
    d.face = cv::Rect2d((f.x + offset.x) * k, (f.y + offset.y) * k, f.width * k, f.height * k);
    d.pixel = k;
    d.body = body_from_face(d.face, p_.body()) & cv::Rect2d(0, 0, frame.cols, frame.rows);
    out.push_back(d);
  }
  return out;
}

// Octave o searches the frame shrunk by k0 * 2^o for faces of min_face_px .. 2.4 min_face_px (the last octave:
// any larger): the cascade's cost per searched pixel is about the same in every octave, so the tiles' pixels
// are the budget. A tile overlaps its neighbours by the largest face it looks for, so every face of its
// octave lies wholly in one tile.
// The scan's finest resolution: the frame shrunk to max_search_pixels (at least face.downscale), then enlarged by
// face.upscale for the smallest faces.
namespace {
double scan_shrink(cv::Size size, const FaceDetectorParams& f) {
  return std::max({1.0, f.downscale, std::sqrt(size.area() / std::max(1.0, f.max_search_pixels))});
}
}  // namespace

double FaceDetector::smallest_scan_face(cv::Size frame_size) const {
  return p_.face.min_face_px * scan_shrink(frame_size, p_.face) / std::max(1.0, p_.face.upscale);
}

void FaceDetector::plan_scan(cv::Size size, Scan& scan) const {
  std::vector<ScanJob>& jobs = scan.jobs;
  jobs.clear();
  scan.planned_for = size;
  scan.next = 0;
  const int min_px = p_.face.min_face_px;
  const double k0 = scan_shrink(size, p_.face);
  std::vector<ScanJob> octave_jobs;
  for (double k = k0;; k *= 2) {
    const cv::Size img(static_cast<int>(std::round(size.width / k)), static_cast<int>(std::round(size.height / k)));
    if (std::min(img.width, img.height) < min_px) break;
    const bool last = std::min(img.width, img.height) / 2 < min_px;
    const int max_face = last ? 0 : static_cast<int>(std::ceil(2.4 * min_px));
    const int overlap = last ? 0 : max_face;
    // The fewest tiles (nx by ny) whose overlapped size fits the budget.
    int nx = 1, ny = 1;
    const auto tile_px = [&](int x, int y) {
      return (static_cast<double>(img.width) / x + (x > 1 ? overlap : 0)) * (static_cast<double>(img.height) / y + (y > 1 ? overlap : 0));
    };
    while (!last && tile_px(nx, ny) > p_.face.scan_slice_pixels && (img.width / nx > 2 * overlap || img.height / ny > 2 * overlap)) {
      if (static_cast<double>(img.width) / nx >= static_cast<double>(img.height) / ny) ++nx; else ++ny;
    }
    octave_jobs.clear();
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int x0 = i * img.width / nx, x1 = (i + 1) * img.width / nx, y0 = j * img.height / ny, y1 = (j + 1) * img.height / ny;
        const cv::Rect tile = cv::Rect(cv::Point(x0 - overlap / 2, y0 - overlap / 2), cv::Point(x1 + overlap / 2, y1 + overlap / 2)) &
                              cv::Rect(cv::Point(), img);
        octave_jobs.push_back({k, tile, max_face});
      }
    jobs.insert(jobs.begin(), octave_jobs.begin(), octave_jobs.end());  // large faces (coarse octaves) first
  }
  // The smallest faces last: an octave on the frame enlarged by face.upscale (faces min_px / upscale .. min_px
  // in the frame), in tiles within the budget.
  const double u = p_.face.upscale;
  if (u > 1.0) {
    const double k = k0 / u;
    const cv::Size img(static_cast<int>(std::round(size.width / k)), static_cast<int>(std::round(size.height / k)));
    const int max_face = static_cast<int>(std::ceil(kUpscaleSizeOverlap * u * min_px));
    const int overlap = max_face;
    int nx = 1, ny = 1;
    const auto tile_px = [&](int x, int y) {
      return (static_cast<double>(img.width) / x + (x > 1 ? overlap : 0)) * (static_cast<double>(img.height) / y + (y > 1 ? overlap : 0));
    };
    while (tile_px(nx, ny) > p_.face.scan_slice_pixels && (img.width / nx > 2 * overlap || img.height / ny > 2 * overlap)) {
      if (static_cast<double>(img.width) / nx >= static_cast<double>(img.height) / ny) ++nx; else ++ny;
    }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int x0 = i * img.width / nx, x1 = (i + 1) * img.width / nx, y0 = j * img.height / ny, y1 = (j + 1) * img.height / ny;
        jobs.push_back({k, cv::Rect(cv::Point(x0 - overlap / 2, y0 - overlap / 2), cv::Point(x1 + overlap / 2, y1 + overlap / 2)) &
                                cv::Rect(cv::Point(), img),
                         max_face});
      }
  }
}

int FaceDetector::scan_tiles(cv::Size frame_size) {
  if (frame_size != scan_.planned_for) plan_scan(frame_size, scan_);
  return static_cast<int>(scan_.jobs.size());
}

std::vector<FaceDetection> FaceDetector::scan_step_all(const cv::Mat& frame) {
  last_step_pixels_ = 0;
  if (frame.empty()) return {};
  if (p_.face.scan_slice_pixels <= 0) {
    last_step_pixels_ = static_cast<double>(frame.total());
    return detect_all(frame);
  }
  return step(frame, scan_);
}

std::vector<FaceDetection> FaceDetector::window_step_all(const cv::Mat& frame, const cv::Rect& roi, double max_face) {
  last_step_pixels_ = 0;
  const cv::Rect r = roi & cv::Rect(0, 0, frame.cols, frame.rows);
  if (r.width < p_.face.min_face_px || r.height < p_.face.min_face_px) return {};
  // What detect_all searches in r: the window (shrunk to max_search_pixels; not when max_face is below its
  // smallest face) and its enlarged copy.
  const double area = static_cast<double>(r.area());
  const double k = std::max({1.0, p_.face.downscale, std::sqrt(area / std::max(1.0, p_.face.max_search_pixels))});
  const double u = p_.face.upscale;
  const bool enlarged = u > 1.0 && k <= 1.0 && area * u * u <= p_.face.max_search_pixels;
  const bool as_is = max_face <= 0 || std::ceil(max_face / k) >= p_.face.min_face_px;
  const double pixels = (as_is ? area / (k * k) : 0.0) + (enlarged ? area * u * u : 0.0);
  if (p_.face.scan_slice_pixels <= 0 || pixels <= p_.face.scan_slice_pixels) {
    last_step_pixels_ = pixels;
    return detect_all(frame, r, 0, max_face);
  }
  // Over the budget (a large box, or a small one's enlarged copy: person12_1's 70x176 px window searched
  // enlarged too cost 35 ms a frame at 1280x720, the whole-frame scan's steps 20): scanned over calls.
  if (r != window_for_) {
    window_for_ = r;
    window_.planned_for = cv::Size();
  }
  return in_frame(step(frame(r), window_, max_face), r, frame);
}

std::vector<FaceDetection> FaceDetector::step(const cv::Mat& frame, Scan& scan, double max_face) {
  if (frame.size() != scan.planned_for) plan_scan(frame.size(), scan);
  if (scan.jobs.empty()) return {};
  grey_of(frame);
  double shrunk_for = 0;
  const int min_px = p_.face.min_face_px;
  std::vector<cv::Rect> faces;
  while (true) {
    const ScanJob& job = scan.jobs[scan.next];
    // The largest face wanted in the job's image (0: any): a job whose smallest face is larger is passed over.
    int max_px = job.max_face;
    if (max_face > 0) {
      const int bound = static_cast<int>(std::ceil(max_face / job.shrink));
      if (bound < min_px) {
        scan.next = (scan.next + 1) % scan.jobs.size();
        if (scan.next == 0) break;
        continue;
      }
      max_px = max_px > 0 ? std::min(max_px, bound) : bound;
    }
    if (last_step_pixels_ > 0 && last_step_pixels_ + job.tile.area() > p_.face.scan_slice_pixels) break;
    if (job.shrink != shrunk_for) {
      if (job.shrink != 1.0)
        cv::resize(grey_, small_,
                   cv::Size(static_cast<int>(std::round(frame.cols / job.shrink)), static_cast<int>(std::round(frame.rows / job.shrink))),
                   0, 0, job.shrink > 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
      else
        small_ = grey_;
      shrunk_for = job.shrink;
    }
    last_step_pixels_ += job.tile.area();
    scan.next = (scan.next + 1) % scan.jobs.size();
    faces.clear();
    cascade_.detectMultiScale(small_(job.tile & cv::Rect(cv::Point(), small_.size())), faces, p_.face.scale_factor,
                              p_.face.min_neighbors, 0, cv::Size(min_px, min_px), cv::Size(max_px, max_px));
    if (!faces.empty()) return sorted_of(faces, job.shrink, job.tile.tl(), frame);
    if (scan.next == 0) break;  // the scan is complete: the next frame starts it again
  }
  return {};
}

std::optional<FaceDetection> FaceDetector::recheck(const cv::Mat& frame, const cv::Rect& roi, double expected,
                                                   double min_share) {
  const cv::Rect r = roi & cv::Rect(0, 0, frame.cols, frame.rows);
  if (r.empty()) return std::nullopt;
  const double sf = p_.face.recheck_scale_factor;
  if (!(expected > 0)) {  // no size expected: the plain search, from its smallest face
    if (r.width < p_.face.min_face_px || r.height < p_.face.min_face_px) return std::nullopt;
    return first(in_frame(detect_all_at(frame(r), 0, 0, sf), r, frame));
  }
  // No face larger than the re-check takes is searched for (at the finer step, the search up to the window's
  // size cost 2.5x the re-check's time): the window enlarged for a far face, shrunk to max_search_pixels for a
  // near one.
  const bool small = p_.face.recheck_small_face_px > 0 && expected < p_.face.recheck_small_face_px;
  const double u = std::min(small ? p_.face.recheck_enlarged_face_px / expected : 1.0,
                            std::sqrt(p_.face.max_search_pixels / static_cast<double>(r.area())));
  // From the cascade's smallest window as shot (its hits there are grouped into the face's box: from min_share of
  // the expected face, the dark-skin user's face was not found at all); enlarged, from min_share.
  const int min_px = small ? std::max(p_.face.min_face_px, static_cast<int>(std::floor(min_share * expected * u)))
                           : p_.face.min_face_px;
  const int max_px = static_cast<int>(std::ceil(kMaxRecheckFaceScale * expected * u));
  if (max_px < min_px) return std::nullopt;
  grey_of(frame(r));
  return first(in_frame(search_enlarged(u, min_px, max_px, frame(r), sf), r, frame));
}

std::vector<FaceDetection> FaceDetector::detect_all(const cv::Mat& frame, const cv::Rect& roi, double min_face,
                                                    double max_face) {
  const cv::Rect r = roi & cv::Rect(0, 0, frame.cols, frame.rows);
  if (r.width < p_.face.min_face_px || r.height < p_.face.min_face_px) return {};
  return in_frame(detect_all(frame(r), min_face, max_face), r, frame);
}

void FaceDetector::grey_of(const cv::Mat& img) {
  if (img.channels() == 3)
    cv::cvtColor(img, grey_, cv::COLOR_BGR2GRAY);
  else
    img.copyTo(grey_);
}

std::vector<FaceDetection> FaceDetector::search_enlarged(double u, int min_px, int max_px, const cv::Mat& img,
                                                         double scale_factor) {
  cv::resize(grey_, small_, cv::Size(), u, u, cv::INTER_LINEAR);
  std::vector<cv::Rect> faces;
  cascade_.detectMultiScale(small_, faces, scale_factor, p_.face.min_neighbors, 0, cv::Size(min_px, min_px),
                            cv::Size(max_px, max_px));
  return sorted_of(faces, 1.0 / u, cv::Point(), img);
}

std::vector<FaceDetection> FaceDetector::in_frame(std::vector<FaceDetection> all, const cv::Rect& r,
                                                  const cv::Mat& frame) const {
  for (FaceDetection& d : all) {
    d.face += cv::Point2d(r.tl());
    d.body = body_from_face(d.face, p_.body()) & cv::Rect2d(0, 0, frame.cols, frame.rows);
  }
  return all;
}

}  // namespace gpilot
