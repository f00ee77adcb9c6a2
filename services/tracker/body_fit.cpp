// The body box of a face checked and fitted against the image (see body_fit.hpp).
#include "body_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace gpilot {

const char* refusal_text(FaceRefusal r) {
  switch (r) {
    case FaceRefusal::kNone: return "";
    case FaceRefusal::kOffFrame: return "body box mostly outside the frame";
    case FaceRefusal::kNoTorso: return "no torso in view under the face";
    case FaceRefusal::kNoBodyColour: return "no body under the face (torso colours are the background's)";
  }
  return "";
}

namespace {

double area(const cv::Rect2d& r) { return r.width > 0 && r.height > 0 ? r.width * r.height : 0.0; }

// Colour histograms over rectangles of one image, each normalised to sum 1 (all zero when empty).
class Histograms {
 public:
  Histograms(const cv::Mat& img, int n) : n_(img.channels() == 3 ? n * n * n : n) {
    bins_.create(img.size(), CV_32S);
    for (int y = 0; y < img.rows; ++y) {
      int* out = bins_.ptr<int>(y);
      if (img.channels() == 3) {
        const cv::Vec3b* px = img.ptr<cv::Vec3b>(y);
        for (int x = 0; x < img.cols; ++x)
          out[x] = (px[x][0] * n / 256 * n + px[x][1] * n / 256) * n + px[x][2] * n / 256;
      } else {
        const uint8_t* px = img.ptr<uint8_t>(y);
        for (int x = 0; x < img.cols; ++x) out[x] = px[x] * n / 256;
      }
    }
  }
  int bins() const { return n_; }
  int bin(int x, int y) const { return bins_.at<int>(y, x); }
  // Sum over rects (clipped to the image), normalised. Returns the pixels counted.
  double of(std::initializer_list<cv::Rect> rects, std::vector<double>& h) const {
    h.assign(static_cast<size_t>(n_), 0.0);
    double count = 0;
    for (const cv::Rect& r0 : rects) {
      const cv::Rect r = r0 & cv::Rect(0, 0, bins_.cols, bins_.rows);
      for (int y = r.y; y < r.br().y; ++y)
        for (int x = r.x; x < r.br().x; ++x) h[static_cast<size_t>(bins_.at<int>(y, x))] += 1.0;
      count += r.area();
    }
    if (count > 0)
      for (double& v : h) v /= count;
    return count;
  }

 private:
  int n_;
  cv::Mat bins_;
};

// The torso under a face: torso_half_width_in_faces either side of the face's centre, from torso_gap_in_faces
// below the chin, torso_height_in_faces tall (not clipped).
cv::Rect2d torso_below(const cv::Rect2d& face, const BodyFitParams& p) {
  const double fw = face.width, fh = face.height, cx = face.x + fw / 2;
  return cv::Rect2d(cx - p.torso_half_width_in_faces * fw, face.y + fh + p.torso_gap_in_faces * fh,
                    2 * p.torso_half_width_in_faces * fw, p.torso_height_in_faces * fh);
}

// What fit_body reads around a face (frame pixels unless said): the face's measures, the preset box and the
// torso sample; the strips beside the box (outside the largest box the fit may give: a person that wide is not
// background); and the region of the frame read, from the chin down to the largest fitted bottom, in a copy
// where the face is at most fit_face_px wide (the cost does not grow with the face).
struct FitRegion {
  cv::Rect2d face;
  double fw = 0, fh = 0, cx = 0, chin = 0;  //!< face width and height, its centre column, the chin's row
  cv::Rect2d box, torso;                    //!< the preset's body box, the torso sample under the face
  double bx = 0;                            //!< the box's centre column
  double beside = 0, outer = 0, half = 0;   //!< a strip's width, half the widest fitted box, the two together
  cv::Rect region;                          //!< the part of the frame read
  cv::Mat img;                              //!< region, shrunk
  double sx = 1, sy = 1;                    //!< img pixels per frame pixel
  cv::Rect to_img(const cv::Rect2d& r) const {
    return cv::Rect(cv::Rect2d((r.x - region.x) * sx, (r.y - region.y) * sy, r.width * sx, r.height * sy)) &
           cv::Rect(0, 0, img.cols, img.rows);
  }
  cv::Rect2d left_strip(double y, double height) const { return cv::Rect2d(bx - half, y, beside, height); }
  cv::Rect2d right_strip(double y, double height) const { return cv::Rect2d(bx + outer, y, beside, height); }
};

// The region fit_body reads; false when none of it is in the frame.
bool read_region(const cv::Mat& frame, const cv::Rect2d& face, const cv::Rect2d& b, const BodyFitParams& p, FitRegion& r) {
  r.face = face;
  r.fw = face.width, r.fh = face.height;
  r.cx = face.x + r.fw / 2, r.chin = face.y + r.fh, r.bx = b.x + b.width / 2;
  r.box = b;
  r.torso = torso_below(face, p);
  r.beside = p.beside_width_in_faces * r.fw;
  r.outer = std::max(1.0, p.fit_max) * b.width / 2;
  r.half = r.outer + r.beside;
  const double bottom = b.y + p.fit_max * b.height;
  r.region = cv::Rect(cv::Rect2d(r.bx - r.half, face.y, 2 * r.half, bottom - face.y)) & cv::Rect(0, 0, frame.cols, frame.rows);
  if (r.region.width < 1 || r.region.height < 1) return false;
  const double s = std::min(1.0, p.fit_face_px / r.fw);
  if (s < 1.0)
    cv::resize(frame(r.region), r.img,
               cv::Size(std::max(1, static_cast<int>(std::lround(r.region.width * s))), std::max(1, static_cast<int>(std::lround(r.region.height * s)))),
               0, 0, cv::INTER_LINEAR);  // not INTER_AREA: that reads every pixel (5 ms for a 240 px face)
  else
    r.img = frame(r.region);
  r.sx = r.img.cols / static_cast<double>(r.region.width), r.sy = r.img.rows / static_cast<double>(r.region.height);
  return true;
}

// Evidence: the torso sample's colours against the strips beside the box at the same height (f.separation, or
// f.refused). False when there is nothing to fit to, or the face is refused: the preset stands.
bool measure_separation(const FitRegion& r, const Histograms& hist, const BodyFitParams& p, BodyFit& f) {
  std::vector<double> t, bg;
  const double torso_px = hist.of({r.to_img(r.torso)}, t);
  const double beside_px =
      hist.of({r.to_img(r.left_strip(r.torso.y, r.torso.height)), r.to_img(r.right_strip(r.torso.y, r.torso.height))}, bg);
  if (torso_px <= 0) {  // none of it in view (only possible with min_torso_in_frame 0: then no evidence, the preset)
    if (p.min_torso_in_frame > 0) f.refused = FaceRefusal::kNoTorso;
    return false;
  }
  if (beside_px <= 0) return false;  // a person filling the frame's width: nothing to compare with, nothing to fit to
  double bc = 0;
  for (size_t i = 0; i < t.size(); ++i) bc += std::sqrt(t[i] * bg[i]);
  f.separation = 1.0 - bc;
  if (p.min_separation > 0 && f.separation < p.min_separation) {
    f.refused = FaceRefusal::kNoBodyColour;
    return false;
  }
  return true;
}

// The centre band under the face, from the torso sample down to the box's bottom.
cv::Rect2d centre_band(const FitRegion& r) { return cv::Rect2d(r.torso.x, r.torso.y, r.torso.width, r.box.br().y - r.torso.y); }

// Per colour bin, 1 where P(person | colour) >= fit_person_p: the centre band (torso and legs, if the box is
// right) and the face's middle (the skin of bare arms and hands) against the strips beside the box over the same
// rows; a colour seen in neither is undecided (0.5). A skin-coloured wall is in the strips too, so it stays
// background.
std::vector<uint8_t> person_colours(const FitRegion& r, const Histograms& hist, const BodyFitParams& p) {
  const cv::Rect band_i = r.to_img(centre_band(r));
  const double k = p.skin_sample_in_faces;
  const cv::Rect skin_i = r.to_img(cv::Rect2d(r.cx - k * r.fw / 2, r.face.y + r.fh / 2 - k * r.fh / 2, k * r.fw, k * r.fh));
  std::vector<double> fg, back;
  hist.of({band_i, skin_i}, fg);
  hist.of({r.to_img(r.left_strip(r.chin, r.box.br().y - r.chin)), r.to_img(r.right_strip(r.chin, r.box.br().y - r.chin))}, back);
  std::vector<uint8_t> person(static_cast<size_t>(hist.bins()));
  for (size_t i = 0; i < person.size(); ++i) {
    const double pp = fg[i] + back[i] > 0 ? fg[i] / (fg[i] + back[i]) : 0.5;
    person[i] = pp >= p.fit_person_p ? 1 : 0;
  }
  return person;
}

// Width: from the face's column out, while the chest band's columns are the person's. A side that runs into
// the frame's edge is not seen (the other side's half-width stands for it).
void measure_width(const FitRegion& r, const Histograms& hist, const std::vector<uint8_t>& person, int frame_cols,
                   const BodyFitParams& p, BodyFit& f) {
  const cv::Rect torso_i = r.to_img(r.torso);
  const auto column_is_person = [&](int x) {
    int n = 0;
    for (int y = torso_i.y; y < torso_i.br().y; ++y) n += person[static_cast<size_t>(hist.bin(x, y))] != 0;
    return torso_i.height > 0 && n >= p.fit_column_fraction * torso_i.height;
  };
  const int c0 = std::clamp(static_cast<int>(std::floor((r.cx - r.region.x) * r.sx)), 0, r.img.cols - 1);
  int left = c0, right = c0;
  const bool centre = column_is_person(c0);  // else the chest band under the face is no silhouette to follow
  while (centre && left > 0 && column_is_person(left - 1)) --left;
  while (centre && right < r.img.cols - 1 && column_is_person(right + 1)) ++right;
  const bool left_seen = centre && !(left == 0 && r.region.x == 0);
  const bool right_seen = centre && !(right == r.img.cols - 1 && r.region.br().x == frame_cols);
  const double left_x = r.region.x + left / r.sx, right_x = r.region.x + (right + 1) / r.sx;
  // The box keeps a margin beside the arms at rest: a silhouette silhouette_width_in_box of the preset's width
  // is the preset.
  const double expected = p.silhouette_width_in_box * r.box.width;
  f.width_seen = left_seen || right_seen;
  if (left_seen && right_seen) {
    f.width_ratio = (right_x - left_x) / expected;
    f.shift = ((left_x + right_x) / 2 - r.cx) / r.fw;
  } else if (left_seen) {
    f.width_ratio = 2 * (r.cx - left_x) / expected;
  } else if (right_seen) {
    f.width_ratio = 2 * (right_x - r.cx) / expected;
  }
}

// Bottom: down the centre band while its rows are the person's (gaps up to fit_gap_in_faces bridged). Rows
// that run into the frame's bottom edge leave the height unseen (the preset's).
void measure_height(const FitRegion& r, const Histograms& hist, const std::vector<uint8_t>& person, int frame_rows,
                    const BodyFitParams& p, BodyFit& f) {
  const cv::Rect torso_i = r.to_img(r.torso);
  const cv::Rect band_i = r.to_img(centre_band(r));
  const auto row_is_person = [&](int y) {
    int n = 0;
    for (int x = band_i.x; x < band_i.br().x; ++x) n += person[static_cast<size_t>(hist.bin(x, y))] != 0;
    return band_i.width > 0 && n >= p.fit_row_fraction * band_i.width;
  };
  const int gap = static_cast<int>(std::floor(p.fit_gap_in_faces * r.fh * r.sy));
  int last = -1;
  for (int y = std::max(0, torso_i.y); y < r.img.rows && y - std::max(last, torso_i.y) <= gap + 1; ++y)
    if (row_is_person(y)) last = y;
  if (last >= 0) {
    const bool to_edge = last == r.img.rows - 1 && r.region.br().y == frame_rows;
    f.height_seen = !to_edge;
    if (f.height_seen) f.height_ratio = (r.region.y + (last + 1) / r.sy - r.box.y) / r.box.height;
  }
}

// The measured ratios applied to the preset only beyond fit_tolerance (the preset is right for most people),
// within [fit_min, fit_max]; f.body and f.box become the fitted ones.
void apply_fit(const cv::Rect2d& face, const BodyFitParams& p, BodyFit& f) {
  const double fw = face.width;
  const cv::Rect2d b = f.box;
  const auto settle = [&](double r, double max) {
    return std::abs(std::log(r)) <= std::log1p(p.fit_tolerance) ? 1.0 : std::clamp(r, p.fit_min, std::max(p.fit_min, max));
  };
  const double wr = f.width_seen ? settle(std::max(f.width_ratio, 1e-3), p.fit_max) : 1.0;
  const double hr = f.height_seen ? settle(std::max(f.height_ratio, 1e-3), std::min(p.fit_max, p.fit_max_height)) : 1.0;
  const double shift = std::abs(f.shift * fw) <= p.fit_tolerance * b.width ? 0.0
                                                                           : std::clamp(f.shift, -p.max_shift_in_faces, p.max_shift_in_faces);
  f.body.width_in_faces *= wr;
  f.body.height_in_faces *= hr;
  if (shift != 0.0) f.body.centre_in_faces = shift;
  f.box = body_from_face(face, f.body);
}

}  // namespace

BodyFit fit_body(const cv::Mat& frame, const cv::Rect2d& face, const BodyProportions& preset, const BodyFitParams& p) {
  BodyFit f;
  f.body = preset;
  f.box = body_from_face(face, preset);
  const cv::Rect2d b = f.box;
  const cv::Rect2d frame_rect(0, 0, frame.cols, frame.rows);
  if (frame.empty() || area(face) <= 0 || area(b) <= 0) {
    f.refused = FaceRefusal::kOffFrame;
    return f;
  }
  f.in_frame = area(b & frame_rect) / area(b);
  if (f.in_frame < p.min_in_frame) {
    f.refused = FaceRefusal::kOffFrame;
    return f;
  }
  const cv::Rect2d torso = torso_below(face, p);
  if (area(torso & frame_rect) < p.min_torso_in_frame * area(torso)) {
    f.refused = FaceRefusal::kNoTorso;
    return f;
  }
  const bool fit = p.fit_min < 1.0 || p.fit_max > 1.0;
  if (p.min_separation <= 0 && !fit) return f;

  FitRegion r;
  if (!read_region(frame, face, b, p, r)) return f;
  const Histograms hist(r.img, p.bins_per_channel);
  if (!measure_separation(r, hist, p, f)) return f;
  if (!fit || f.separation < p.fit_min_separation) return f;
  const std::vector<uint8_t> person = person_colours(r, hist, p);
  measure_width(r, hist, person, frame.cols, p, f);
  measure_height(r, hist, person, frame.rows, p, f);
  apply_fit(face, p, f);
  return f;
}

std::vector<float> torso_colours(const cv::Mat& frame, const cv::Rect2d& face, const BodyFitParams& p, int bins,
                                 double dark_level) {
  std::vector<float> h;
  if (frame.empty() || frame.type() != CV_8UC3 || !(face.width > 0 && face.height > 0) || bins < 1) return h;
  const double fw = face.width;
  const cv::Rect torso = cv::Rect(torso_below(face, p)) & cv::Rect(0, 0, frame.cols, frame.rows);
  if (torso.width < 1 || torso.height < 1) return h;
  const int step = std::max(1, static_cast<int>(fw / p.fit_face_px));
  const double min_sum = 3.0 * dark_level;
  h.assign(static_cast<size_t>(bins * bins), 0.0f);
  double n = 0;
  for (int y = torso.y; y < torso.br().y; y += step) {
    const cv::Vec3b* row = frame.ptr<cv::Vec3b>(y);
    for (int x = torso.x; x < torso.br().x; x += step) {
      const double b = row[x][0], g = row[x][1], r = row[x][2], sum = b + g + r;
      if (sum < min_sum || sum <= 0) continue;
      const int ri = std::min(bins - 1, static_cast<int>(r / sum * bins));
      const int gi = std::min(bins - 1, static_cast<int>(g / sum * bins));
      h[static_cast<size_t>(ri * bins + gi)] += 1.0f;
      n += 1;
    }
  }
  if (n <= 0) return {};
  for (float& v : h) v = static_cast<float>(v / n);
  return h;
}

double colour_match(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.empty() || b.empty() || a.size() != b.size()) return -1.0;
  double bc = 0;
  for (size_t i = 0; i < a.size(); ++i) bc += std::sqrt(static_cast<double>(a[i]) * b[i]);
  return bc;
}

}  // namespace gpilot
