// Rendering of the synthetic world: background photograph as a far backdrop, the person as projected 3-D
// body parts (limbs as tapered capsules, the head as the portrait on a plane), then the scenario's nuisances.
#include "synthetic_world.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "body_proportions.hpp"
#include "paths.hpp"

namespace gpilot {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr int kShift = 4;  // sub-pixel bits for OpenCV drawing
constexpr double kOne = 1 << kShift;

// The portrait: the part of astronaut.png pasted as the head, and the box the Haar cascade
// (haarcascade_frontalface_alt2, scale 1.1, 5 neighbours) finds in the full portrait: 97 x 97 at (177, 66).
const cv::Rect kHeadCrop(140, 10, 170, 168);
const cv::Rect2d kFaceInCrop(177 - 140, 66 - 10, 97, 97);
// On the 25..55 px faces of 2..4 m the cascade's box is larger than on the full portrait, by 1.06..1.11 with
// the same centre (tests/unit/capture/test_synthetic_face.cpp): the truth face box is scaled by this.
constexpr double kHaarBoxScale = 1.1;
// Head outline (hair included) and the face inside it, crop pixels. The outline ends 0.15 face boxes below
// the face box (it trims the chin's tip), so that no face skin reaches below the hands stage's face band.
const cv::RotatedRect kHeadOutline(cv::Point2f(85, 86), cv::Size2f(150, 162), 0);
const cv::RotatedRect kFaceOval(cv::Point2f(85, 110), cv::Size2f(92, 124), 0);
constexpr double kHairGain = 0.3;  // the portrait's fair hair is skin-coloured; darkened, it is not

const cv::Scalar kTurtleneck(44, 40, 38);
// The back of the head, seen when the person turns away: hair over the portrait's head outline (its size and
// centre in face boxes: kHeadOutline against the face oval).
const cv::Scalar kHair(35, 45, 60);
constexpr double kHeadHalfWidth = 0.75, kHeadHalfHeight = 0.82, kHeadAboveFaceCentre = 0.25;
const cv::Scalar kShoes(30, 30, 32);

cv::Point fixed(const cv::Point2d& p) {
  return {static_cast<int>(std::lround(p.x * kOne)), static_cast<int>(std::lround(p.y * kOne))};
}

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

cv::Mat read_image(const std::string& path, int flags) {
  const std::string p = resolve_project_path(path);
  cv::Mat m = cv::imread(p, flags);
  if (m.empty()) throw std::runtime_error("synthetic world: cannot read image '" + p + "'");
  return m;
}

// The colours of one tone from the skin tones CSV (tone,b,g,r).
std::vector<cv::Vec3b> read_skin_tone(const std::string& path, const std::string& tone) {
  const std::string p = resolve_project_path(path);
  std::ifstream in(p);
  if (!in) throw std::runtime_error("synthetic world: cannot read skin tones '" + p + "'");
  std::vector<cv::Vec3b> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string name, b, g, r;
    if (!std::getline(ss, name, ',') || !std::getline(ss, b, ',') || !std::getline(ss, g, ',') || !std::getline(ss, r))
      throw std::runtime_error("synthetic world: " + p + ": bad line '" + line + "'");
    if (name == tone)
      out.emplace_back(static_cast<uchar>(std::stoi(b)), static_cast<uchar>(std::stoi(g)), static_cast<uchar>(std::stoi(r)));
  }
  if (out.empty()) throw std::runtime_error("synthetic world: " + p + ": no colours for skin tone '" + tone + "'");
  return out;
}

// Draws a shape on the frame (anti-aliased) and, if wanted, on the label image (hard edges).
void paint(cv::Mat& img, cv::Mat* labels, PartLabel label, const cv::Scalar& colour,
           const std::function<void(cv::Mat&, const cv::Scalar&, int)>& draw) {
  draw(img, colour, cv::LINE_AA);
  if (labels) draw(*labels, cv::Scalar(static_cast<double>(label)), cv::LINE_8);
}

// A limb: a tapered capsule from a (radius ra) to b (radius rb), pixels.
void capsule(cv::Mat& m, const cv::Point2d& a, const cv::Point2d& b, double ra, double rb, const cv::Scalar& c, int line) {
  cv::Point2d d = b - a;
  const double n = std::hypot(d.x, d.y);
  if (n > 1e-9) {
    const cv::Point2d perp(-d.y / n, d.x / n);
    const cv::Point pts[4] = {fixed(a + perp * ra), fixed(b + perp * rb), fixed(b - perp * rb), fixed(a - perp * ra)};
    cv::fillConvexPoly(m, pts, 4, c, line, kShift);
  }
  cv::circle(m, fixed(a), static_cast<int>(std::lround(ra * kOne)), c, cv::FILLED, line, kShift);
  cv::circle(m, fixed(b), static_cast<int>(std::lround(rb * kOne)), c, cv::FILLED, line, kShift);
}

void ellipse(cv::Mat& m, const cv::Point2d& centre, const cv::Point2d& axis_dir, double half_len, double half_width,
             const cv::Scalar& c, int line) {
  const double angle = std::atan2(axis_dir.y, axis_dir.x) / kDeg;
  cv::ellipse(m, fixed(centre), cv::Size(static_cast<int>(std::lround(half_len * kOne)), static_cast<int>(std::lround(half_width * kOne))),
              angle, 0, 360, c, cv::FILLED, line, kShift);
}

cv::Rect bounds(const std::vector<cv::Point2d>& pts, double margin, const cv::Size& size) {
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (const auto& p : pts) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  const cv::Rect r(cv::Point(static_cast<int>(std::floor(std::max(-1e6, x0 - margin))), static_cast<int>(std::floor(std::max(-1e6, y0 - margin)))),
                   cv::Point(static_cast<int>(std::ceil(std::min(1e6, x1 + margin))) + 1, static_cast<int>(std::ceil(std::min(1e6, y1 + margin))) + 1));
  return r & cv::Rect(cv::Point(0, 0), size);
}

// The wall's texture: kWallTexel metres a pixel, kWallTexW x kWallTexH pixels (8 m x 4 m), periodic both ways.
constexpr double kWallTexel = 0.005;
constexpr int kWallTexW = 1600, kWallTexH = 800;
constexpr int kWallBoard = 25;  // wood: boards 12.5 cm wide (64 a period)
// The wall's light: a lamp up and to the image's left of the person, falloff scale kLampSpread metres.
constexpr double kLampAlong = -0.8, kLampHeight = 2.4, kLampSpread = 1.6;

// A periodic Gaussian blur (the texture tiles): wrap-pad, blur, crop.
cv::Mat blur_wrapped(const cv::Mat& m, double sx, double sy) {
  const int px = static_cast<int>(std::ceil(4 * sx)) + 1, py = static_cast<int>(std::ceil(4 * sy)) + 1;
  cv::Mat padded, blurred;
  cv::copyMakeBorder(m, padded, py, py, px, px, cv::BORDER_WRAP);
  cv::GaussianBlur(padded, blurred, cv::Size(2 * px + 1, 2 * py + 1), sx, sy, cv::BORDER_REFLECT);
  return blurred(cv::Rect(px, py, m.cols, m.rows)).clone();
}

// Zero-mean, unit-deviation random field (CV_32F) with features of about sx x sy texels, periodic.
cv::Mat periodic_noise(cv::RNG& rng, double sx, double sy) {
  cv::Mat n(kWallTexH, kWallTexW, CV_32F);
  rng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
  n = blur_wrapped(n, sx, sy);
  cv::Scalar mean, dev;
  cv::meanStdDev(n, mean, dev);
  n = (n - mean[0]) / std::max(dev[0], 1e-9);
  return n;
}

// Smooth, periodic low-frequency field: a few waves of whole cycles across the texture, unit deviation.
cv::Mat periodic_waves(cv::RNG& rng, int max_kx, int max_ky, int waves) {
  cv::Mat n(kWallTexH, kWallTexW, CV_32F, cv::Scalar(0));
  std::vector<std::array<double, 4>> w;  // kx, ky, phase, amplitude
  for (int i = 0; i < waves; ++i) {
    const int kx = rng.uniform(0, max_kx + 1), ky = rng.uniform(0, max_ky + 1);
    if (kx == 0 && ky == 0) continue;
    w.push_back({double(kx), double(ky), rng.uniform(0.0, 2 * M_PI), 1.0 / std::hypot(kx, 2.0 * ky)});
  }
  for (int y = 0; y < n.rows; ++y) {
    float* row = n.ptr<float>(y);
    for (int x = 0; x < n.cols; ++x) {
      double v = 0;
      for (const auto& a : w) v += a[3] * std::sin(2 * M_PI * (a[0] * x / kWallTexW + a[1] * y / kWallTexH) + a[2]);
      row[x] = static_cast<float>(v);
    }
  }
  cv::Scalar mean, dev;
  cv::meanStdDev(n, mean, dev);
  return (n - mean[0]) / std::max(dev[0], 1e-9);
}

// The wall's texture at full brightness (shading is applied per frame from the wall coordinates). Fixed
// random streams: the same wall for every seed.
cv::Mat make_wall_texture(const ScenarioWall& wall) {
  const cv::Vec3f base(float(wall.bgr[0]), float(wall.bgr[1]), float(wall.bgr[2]));
  cv::Mat tex(kWallTexH, kWallTexW, CV_32FC3, cv::Scalar(base[0], base[1], base[2]));
  if (wall.texture == "plaster") {
    // Mottling over tens of centimetres (5 %), trowel marks of a few centimetres (3 %), grain (2.5 %), and a
    // slight warm/cool drift of the hue (1.5 % on red against blue).
    cv::RNG rng(0x9A57E12ull);
    const cv::Mat mottle = periodic_waves(rng, 12, 6, 24), trowel = periodic_noise(rng, 6, 4), grain = periodic_noise(rng, 0.8, 0.8);
    const cv::Mat hue = periodic_waves(rng, 8, 4, 12);
    for (int y = 0; y < tex.rows; ++y) {
      cv::Vec3f* t = tex.ptr<cv::Vec3f>(y);
      for (int x = 0; x < tex.cols; ++x) {
        const float l = 1.0f + 0.05f * mottle.at<float>(y, x) + 0.03f * trowel.at<float>(y, x) + 0.025f * grain.at<float>(y, x);
        const float h = 0.015f * hue.at<float>(y, x);
        t[x] = cv::Vec3f(base[0] * l * (1 - h), base[1] * l, base[2] * l * (1 + h));
      }
    }
  } else if (wall.texture == "wood") {
    // Vertical boards: each with its own tone and redness, wavy grain lines (darker, more saturated late wood)
    // 1.5-3 cm apart, long fibres, and a dark joint with a shaded edge between boards.
    cv::RNG rng(0x3A11B0A7ull);
    const cv::Mat fibre = periodic_noise(rng, 0.7, 8.0);
    const int boards = kWallTexW / kWallBoard;
    struct Board { double tone, red, spacing, phase, wave_amp, wave_len, wave_phase; };
    std::vector<Board> b(static_cast<size_t>(boards));
    for (auto& k : b)
      k = {rng.uniform(0.86, 1.08), rng.uniform(-0.04, 0.04), rng.uniform(3.0, 6.0), rng.uniform(0.0, 1.0),
           rng.uniform(1.0, 4.0), double(kWallTexH) / rng.uniform(1, 4), rng.uniform(0.0, 2 * M_PI)};
    const cv::Vec3f late(0.76f, 0.83f, 0.92f);  // late wood: darker, blue and green more than red
    for (int y = 0; y < tex.rows; ++y) {
      cv::Vec3f* t = tex.ptr<cv::Vec3f>(y);
      for (int x = 0; x < tex.cols; ++x) {
        const Board& k = b[static_cast<size_t>(x / kWallBoard)];
        const int xl = x % kWallBoard;
        const double warp = k.wave_amp * std::sin(2 * M_PI * y / k.wave_len + k.wave_phase);
        const double ring = 0.5 + 0.5 * std::sin(2 * M_PI * ((xl + warp) / k.spacing + k.phase));
        const float g = static_cast<float>(std::pow(ring, 4.0));
        const float l = static_cast<float>(k.tone) * (1.0f + 0.03f * fibre.at<float>(y, x));
        const float joint = xl < 2 ? 0.45f : xl == 2 ? 0.85f : xl == kWallBoard - 1 ? 1.04f : 1.0f;
        for (int c = 0; c < 3; ++c) {
          const float red = c == 2 ? 1.0f + static_cast<float>(k.red) : c == 0 ? 1.0f - static_cast<float>(k.red) : 1.0f;
          t[x][c] = base[c] * l * red * joint * (1.0f - g + g * late[c]);
        }
      }
    }
  }
  cv::Mat out;
  blur_wrapped(tex, 0.6, 0.6).convertTo(out, CV_8UC3);
  return out;
}

}  // namespace

// The camera of one frame and the person's frame, with projection between them.
struct SyntheticWorld::View {
  cv::Vec3d c, right, down, fwd;   // camera centre and axes, NED
  double f = 0, cx = 0, cy = 0;
  cv::Vec3d origin, left, up, front;  // person frame: origin at the feet, axes in NED
  double yaw = 0, pitch = 0;

  cv::Vec3d world(const cv::Point3d& p) const { return origin + left * p.x + up * p.y + front * p.z; }
  double depth(const cv::Point3d& p) const { return (world(p) - c).dot(fwd); }
  cv::Point2d project(const cv::Point3d& p) const {
    const cv::Vec3d d = world(p) - c;
    const double z = std::max(d.dot(fwd), 0.05);  // parts behind the camera are squashed onto it, not mirrored
    return {cx + f * d.dot(right) / z, cy + f * d.dot(down) / z};
  }
  double px(double metres, const cv::Point3d& at) const { return f * metres / std::max(depth(at), 0.05); }
};

SyntheticWorld::SyntheticWorld(const SyntheticParams& params, Scenario scenario, uint64_t seed)
    : params_(params), scenario_(std::move(scenario)), seed_(seed) {
  dims_ = FigureDims{}.scaled(params_.face_box_m);
  focal_ = 0.5 * params_.width / std::tan(0.5 * params_.hfov_deg * kDeg);

  // Backdrop: the photograph scaled to 1.5 frame heights, then photo | mirror | photo | mirror so that it wraps.
  cv::Mat photo = read_image(scenario_.background(), cv::IMREAD_COLOR);
  {
    const BackgroundGrade& g = scenario_.background_grade();
    cv::Mat grey;
    cv::cvtColor(photo, grey, cv::COLOR_BGR2GRAY);
    cv::cvtColor(grey, grey, cv::COLOR_GRAY2BGR);
    cv::addWeighted(photo, g.saturation, grey, 1.0 - g.saturation, 0.0, photo);
    cv::multiply(photo, cv::Scalar(g.blue_gain, 1.0, g.red_gain), photo);
  }
  const int ph = static_cast<int>(std::ceil(1.5 * params_.height));
  const int pw = std::max(static_cast<int>(std::lround(photo.cols * double(ph) / photo.rows)), params_.width);
  cv::Mat scaled, mirrored;
  cv::resize(photo, scaled, cv::Size(pw, ph), 0, 0, cv::INTER_AREA);
  if (scenario_.background_grade().blur_sigma > 0)
    cv::GaussianBlur(scaled, scaled, cv::Size(), scenario_.background_grade().blur_sigma);
  cv::flip(scaled, mirrored, 1);
  cv::hconcat(std::vector<cv::Mat>{scaled, mirrored, scaled, mirrored}, panorama_);
  pano_period_ = 2.0 * pw;

  // Head: the portrait's crop with an elliptical alpha and the hair darkened.
  const cv::Mat portrait = read_image(params_.face_image, cv::IMREAD_COLOR);
  if (portrait.cols < kHeadCrop.br().x || portrait.rows < kHeadCrop.br().y)
    throw std::runtime_error("synthetic world: face image '" + params_.face_image + "' is not the 512x512 astronaut portrait");
  cv::Mat crop = portrait(kHeadCrop).clone();
  cv::Mat alpha(crop.size(), CV_8UC1, cv::Scalar(0)), face(crop.size(), CV_8UC1, cv::Scalar(0));
  cv::ellipse(alpha, kHeadOutline, cv::Scalar(255), cv::FILLED, cv::LINE_AA);
  cv::ellipse(face, kFaceOval, cv::Scalar(255), cv::FILLED, cv::LINE_AA);
  cv::GaussianBlur(face, face, cv::Size(9, 9), 0);
  // Face tint (person.tint_face): per-channel gains that take the face's mean colour to the tone's mean colour,
  // applied inside the face oval (fading out with it); features and shading are kept.
  cv::Vec3d tint(1.0, 1.0, 1.0);
  const std::vector<cv::Vec3b> tones = read_skin_tone(params_.skin_tones, scenario_.person().skin_tone);
  if (scenario_.person().tint_face) {
    const cv::Scalar face_mean = cv::mean(crop, face > 200);
    cv::Vec3d tone_mean(0, 0, 0);
    for (const auto& t : tones) tone_mean += cv::Vec3d(t[0], t[1], t[2]);
    tone_mean *= 1.0 / static_cast<double>(tones.size());
    for (int c = 0; c < 3; ++c) tint[c] = tone_mean[c] / std::max(face_mean[c], 1.0);
  }
  for (int y = 0; y < crop.rows; ++y)
    for (int x = 0; x < crop.cols; ++x) {
      const double w = face.at<uchar>(y, x) / 255.0;
      const double gain = kHairGain + (1.0 - kHairGain) * w;
      cv::Vec3b& p = crop.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) p[c] = cv::saturate_cast<uchar>(p[c] * gain * (1.0 + (tint[c] - 1.0) * w));
    }
  std::vector<cv::Mat> channels;
  cv::split(crop, channels);
  channels.push_back(alpha);  // B, G, R and the head outline as alpha
  cv::Mat bgra;
  cv::merge(channels, bgra);
  head_levels_.push_back(bgra);
  while (head_levels_.back().cols > 24) {
    cv::Mat next;
    cv::pyrDown(head_levels_.back(), next);
    head_levels_.push_back(next);
  }
  head_face_px_ = kFaceInCrop;

  // Skin: a frame-sized texture of real skin colours of the person's tone (fixed, independent of the seed).
  cv::Mat tile(64, 64, CV_8UC3);
  cv::RNG tile_rng(0x5EED5C1Eu);
  for (int y = 0; y < tile.rows; ++y)
    for (int x = 0; x < tile.cols; ++x) tile.at<cv::Vec3b>(y, x) = tones[static_cast<size_t>(tile_rng.uniform(0, static_cast<int>(tones.size())))];
  cv::GaussianBlur(tile, tile, cv::Size(3, 3), 0, 0, cv::BORDER_WRAP);
  cv::repeat(tile, (params_.height + 63) / 64, (params_.width + 63) / 64, skin_plane_);

  // Wall: a vertical plane distance_m behind the person, on the scenario camera's line to them, facing it.
  if (scenario_.wall().present) {
    const ScenarioWall& w = scenario_.wall();
    const auto& person = scenario_.person();
    const CameraPose& cam = scenario_.camera();
    cv::Vec3d dir(person.north - cam.north, person.east - cam.east, 0.0);
    if (cv::norm(dir) < 1e-6) dir = cv::Vec3d(std::cos(cam.yaw), std::sin(cam.yaw), 0.0);
    dir = cv::normalize(dir);
    wall_centre_ = cv::Vec3d(person.north, person.east, 0.0) + dir * w.distance_m;
    wall_normal_ = -dir;
    wall_along_ = cv::Vec3d(-dir[1], dir[0], 0.0);  // to the right as seen from the camera
    wall_texture_ = make_wall_texture(w);
  }

  // Sensor noise: one bank of unit Gaussian noise (x 64), read at a per-frame offset.
  cv::RNG rng(splitmix64(seed_));
  noise_bank_.create(params_.height + 64, params_.width + 64, CV_16SC3);
  rng.fill(noise_bank_, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(64));
  for (double& p : shake_phase_) p = rng.uniform(0.0, 2.0 * M_PI);
}

void SyntheticWorld::draw_background(cv::Mat& img, const View& v) const {
  // The photograph hangs at background_distance_m in front of the scenario's camera: yaw and sideways motion
  // slide it, vertical motion and pitch shift it, forward motion scales it (parallax of a far plane).
  const CameraPose& ref = scenario_.camera();
  const double dn = v.c[0] - ref.north, de = v.c[1] - ref.east, dd = v.c[2] - ref.down;
  const double fwd = dn * std::cos(ref.yaw) + de * std::sin(ref.yaw);
  const double lat = -dn * std::sin(ref.yaw) + de * std::cos(ref.yaw);
  const double dist = params_.background_distance_m;
  const double s = std::clamp(dist / std::max(dist - fwd, 1e-3), 0.5, 4.0);
  // Reference: the middle of the second unmirrored copy; wrapped into [period/2, 3 period/2), where a window
  // of up to a photo's width either side stays inside the four copies.
  const double half_period = 0.5 * pano_period_;
  double x0 = 2.5 * half_period + focal_ * (std::remainder(v.yaw - ref.yaw, 2 * M_PI) + lat / dist);
  x0 = half_period + std::fmod(std::fmod(x0 - half_period, pano_period_) + pano_period_, pano_period_);
  const double y0 = 0.5 * panorama_.rows + focal_ * (dd / dist - std::tan(v.pitch));
  const cv::Matx23d inv(1.0 / s, 0, x0 - v.cx / s, 0, 1.0 / s, y0 - v.cy / s);
  cv::warpAffine(panorama_, img, inv, img.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REFLECT);
}

void SyntheticWorld::draw_wall(cv::Mat& img, cv::Mat* labels, const View& v) const {
  const ScenarioWall& w = scenario_.wall();
  cv::Mat map_x(img.size(), CV_32F), map_y(img.size(), CV_32F), shade(img.size(), CV_32F);
  cv::Mat hit(img.size(), CV_8U, cv::Scalar(0));
  const double c_n = (wall_centre_ - v.c).dot(wall_normal_);  // < 0: the camera is in front of the wall
  const double two_l2 = 2.0 * kLampSpread * kLampSpread;
  for (int y = 0; y < img.rows; ++y) {
    float* mx = map_x.ptr<float>(y);
    float* my = map_y.ptr<float>(y);
    float* sh = shade.ptr<float>(y);
    uchar* h = hit.ptr<uchar>(y);
    const cv::Vec3d row = v.fwd + v.down * ((y - v.cy) / v.f);
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3d d = row + v.right * ((x - v.cx) / v.f);
      const double dn = d.dot(wall_normal_);
      mx[x] = my[x] = -1.0f;
      if (std::fabs(dn) < 1e-9) continue;
      const double t = c_n / dn;
      if (t <= 0.0) continue;
      const cv::Vec3d p = v.c + d * t - wall_centre_;
      const double u = p.dot(wall_along_), height = -p[2];
      if (w.width_m > 0 && std::fabs(u) > 0.5 * w.width_m) continue;
      if (w.height_m > 0 && (height < 0 || height > w.height_m)) continue;
      const double col = u / kWallTexel + 0.5 * kWallTexW, row_px = (4.0 - height) / kWallTexel;
      mx[x] = static_cast<float>(col - kWallTexW * std::floor(col / kWallTexW));
      my[x] = static_cast<float>(row_px - kWallTexH * std::floor(row_px / kWallTexH));
      const double r2 = (u - kLampAlong) * (u - kLampAlong) + (height - kLampHeight) * (height - kLampHeight);
      sh[x] = static_cast<float>(1.0 - w.shading * (1.0 - std::exp(-r2 / two_l2)));
      h[x] = 1;
    }
  }
  cv::Mat wall;
  cv::remap(wall_texture_, wall, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_WRAP);
  for (int y = 0; y < img.rows; ++y) {
    const uchar* h = hit.ptr<uchar>(y);
    const float* sh = shade.ptr<float>(y);
    const cv::Vec3b* src = wall.ptr<cv::Vec3b>(y);
    cv::Vec3b* dst = img.ptr<cv::Vec3b>(y);
    uchar* l = labels ? labels->ptr<uchar>(y) : nullptr;
    for (int x = 0; x < img.cols; ++x) {
      if (!h[x]) continue;
      for (int c = 0; c < 3; ++c) dst[x][c] = cv::saturate_cast<uchar>(src[x][c] * sh[x]);
      if (l) l[x] = static_cast<uchar>(PartLabel::Wall);
    }
  }
}

void SyntheticWorld::blend_skin(cv::Mat& img, const cv::Mat& alpha, const cv::Rect& roi) const {
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const uchar* a = alpha.ptr<uchar>(y);
    const cv::Vec3b* s = skin_plane_.ptr<cv::Vec3b>(y);
    cv::Vec3b* d = img.ptr<cv::Vec3b>(y);
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      if (!a[x]) continue;
      const int w = a[x];
      for (int c = 0; c < 3; ++c) d[x][c] = static_cast<uchar>((s[x][c] * w + d[x][c] * (255 - w) + 127) / 255);
    }
  }
}

bool SyntheticWorld::faces_away(const View& v, double step_x) const {
  const cv::Point3d face(step_x, dims_.face_top - 0.5 * dims_.face_box, 0.0);
  return (v.c - v.world(face)).dot(v.front) <= 0.0;  // the camera behind the face's plane
}

void SyntheticWorld::draw_head(cv::Mat& img, cv::Mat* labels, const View& v, double step_x) const {
  // Turned away: the back of the head, hair over a head-sized ellipse.
  if (faces_away(v, step_x)) {
    const cv::Point3d head_centre(step_x, dims_.face_top - (0.5 - kHeadAboveFaceCentre) * dims_.face_box, 0.0);
    const cv::Point2d c = v.project(head_centre);
    const cv::Point2d top = v.project(head_centre + cv::Point3d(0, 1, 0));
    const double half_w = v.px(kHeadHalfWidth * dims_.face_box, head_centre);
    const double half_h = v.px(kHeadHalfHeight * dims_.face_box, head_centre);
    paint(img, labels, PartLabel::Head, kHair,
          [&](cv::Mat& m, const cv::Scalar& col, int line) { ellipse(m, c, top - c, half_h, half_w, col, line); });
    return;
  }
  const cv::Mat& base = head_levels_.front();
  const double mpp = dims_.face_box / head_face_px_.width;  // metres per portrait pixel
  const double face_cx = head_face_px_.x + 0.5 * head_face_px_.width;
  auto corner = [&](double col, double row) {
    return v.project({step_x + (col - face_cx) * mpp, dims_.face_top - (row - head_face_px_.y) * mpp, 0.02});
  };
  const std::vector<cv::Point2d> dst = {corner(0, 0), corner(base.cols, 0), corner(base.cols, base.rows), corner(0, base.rows)};
  const cv::Rect roi = bounds(dst, 1.0, img.size());
  if (roi.area() == 0) return;
  const double width_px = std::hypot(dst[1].x - dst[0].x, dst[1].y - dst[0].y);
  size_t level = 0;
  while (level + 1 < head_levels_.size() && head_levels_[level + 1].cols >= width_px) ++level;
  const cv::Mat& tex = head_levels_[level];
  const cv::Point2f src_pts[4] = {{0, 0}, {float(tex.cols), 0}, {float(tex.cols), float(tex.rows)}, {0, float(tex.rows)}};
  cv::Point2f dst_pts[4];
  for (int i = 0; i < 4; ++i) dst_pts[i] = cv::Point2f(float(dst[i].x - roi.x), float(dst[i].y - roi.y));
  const cv::Mat h = cv::getPerspectiveTransform(src_pts, dst_pts);
  cv::Mat patch;
  cv::warpPerspective(tex, patch, h, roi.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0));
  for (int y = 0; y < roi.height; ++y) {
    const cv::Vec4b* p = patch.ptr<cv::Vec4b>(y);
    cv::Vec3b* d = img.ptr<cv::Vec3b>(roi.y + y) + roi.x;
    uchar* l = labels ? labels->ptr<uchar>(roi.y + y) + roi.x : nullptr;
    for (int x = 0; x < roi.width; ++x) {
      const int a = p[x][3];
      if (!a) continue;
      for (int c = 0; c < 3; ++c) d[x][c] = static_cast<uchar>((p[x][c] * a + d[x][c] * (255 - a) + 127) / 255);
      if (l && a >= 128) l[x] = static_cast<uchar>(PartLabel::Head);
    }
  }
}

void SyntheticWorld::draw_person(cv::Mat& img, cv::Mat* labels, const View& v, const FigurePose& pose,
                                 const ScenarioPerson& person) const {
  const FigureDims& d = dims_;
  const double sx = pose.step_x;
  const cv::Scalar shirt(person.shirt_bgr[0], person.shirt_bgr[1], person.shirt_bgr[2]);
  const cv::Scalar trousers(person.trousers_bgr[0], person.trousers_bgr[1], person.trousers_bgr[2]);
  auto P = [&](double x, double y, double z = 0.0) { return cv::Point3d(sx + x, y, z); };
  auto limb = [&](PartLabel lab, const cv::Scalar& col, const cv::Point3d& a, const cv::Point3d& b, double ra, double rb) {
    const cv::Point2d pa = v.project(a), pb = v.project(b);
    const double rpa = v.px(ra, a), rpb = v.px(rb, b);
    paint(img, labels, lab, col, [&](cv::Mat& m, const cv::Scalar& c, int line) { capsule(m, pa, pb, rpa, rpb, c, line); });
  };

  // Legs and shoes.
  for (double side : {-1.0, 1.0}) {
    limb(PartLabel::Legs, trousers, P(side * d.leg_x, d.hip_y), P(side * d.foot_x, d.ankle_y), d.leg_half_top, d.leg_half_ankle);
    const cv::Point3d foot = P(side * d.foot_x, 0.03, 0.06);
    const cv::Point2d c = v.project(foot);
    const double hl = v.px(0.07, foot), hw = v.px(0.035, foot);
    paint(img, labels, PartLabel::Legs, kShoes, [&](cv::Mat& m, const cv::Scalar& col, int line) { ellipse(m, c, {1, 0}, hl, hw, col, line); });
  }
  // Torso (a hexagon, narrower at the waist) with rounded shoulders, and the turtleneck.
  {
    const std::vector<cv::Point3d> outline = {P(-d.torso_half_top, d.torso_top), P(d.torso_half_top, d.torso_top),
                                              P(d.torso_half_waist, d.waist_y),   P(d.torso_half_hip, d.hip_y),
                                              P(-d.torso_half_hip, d.hip_y),      P(-d.torso_half_waist, d.waist_y)};
    std::vector<cv::Point> pts;
    for (const auto& p : outline) pts.push_back(fixed(v.project(p)));
    paint(img, labels, PartLabel::Torso, shirt, [&](cv::Mat& m, const cv::Scalar& c, int line) {
      cv::fillPoly(m, std::vector<std::vector<cv::Point>>{pts}, c, line, kShift);
    });
    for (double side : {-1.0, 1.0})
      limb(PartLabel::Torso, shirt, P(side * (d.shoulder_x - 0.01), d.shoulder_y + 0.005), P(side * d.shoulder_x * 0.6, d.torso_top - 0.03),
           d.upper_arm_half * 1.25, d.upper_arm_half * 1.2);
    // Horizontal stripes that move with the shirt: texture on the person for a tracker to hold on to.
    const cv::Scalar stripe = shirt * 0.55;
    for (double y = d.hip_y + 0.03; y < d.torso_top - 0.04; y += 0.05) {
      const double half = y > d.waist_y ? d.torso_half_waist + (d.torso_half_top - d.torso_half_waist) * (y - d.waist_y) / (d.torso_top - d.waist_y)
                                        : d.torso_half_hip + (d.torso_half_waist - d.torso_half_hip) * (y - d.hip_y) / (d.waist_y - d.hip_y);
      const cv::Point2d a = v.project(P(-half + 0.006, y)), b = v.project(P(half - 0.006, y));
      const int thick = std::max(1, static_cast<int>(std::lround(v.px(0.015, P(0, y)))));
      cv::line(img, fixed(a), fixed(b), stripe, thick, cv::LINE_AA, kShift);
    }
    limb(PartLabel::Torso, kTurtleneck, P(0, d.face_top - d.face_box), P(0, d.torso_top), d.neck_half, d.neck_half * 1.15);
  }
  draw_head(img, labels, v, sx);

  // Arms, the one further from the camera first: sleeve, bare skin (upper arm end and forearm), hand.
  std::array<const ArmJoints*, 2> arms = {&pose.right, &pose.left};
  if (v.depth(pose.left.hand) > v.depth(pose.right.hand)) std::swap(arms[0], arms[1]);
  cv::Mat alpha(img.size(), CV_8UC1, cv::Scalar(0));
  for (const ArmJoints* arm : arms) {
    const bool right = arm == &pose.right;
    const cv::Point3d sleeve_end = arm->shoulder + (arm->elbow - arm->shoulder) * d.sleeve;
    const cv::Point2d ps = v.project(sleeve_end), pe = v.project(arm->elbow), pw = v.project(arm->wrist);
    const cv::Point2d ph = v.project(arm->hand), pt = v.project(arm->hand_tip);
    const double r_up = v.px(d.upper_arm_half, sleeve_end), r_el = v.px(d.forearm_half * 1.1, arm->elbow);
    const double r_wr = v.px(d.forearm_half * 0.8, arm->wrist);
    const double hand_len = v.px(0.5 * d.hand_length, arm->hand), hand_w = v.px(d.hand_half_width, arm->hand);
    const PartLabel skin_label = right ? PartLabel::RightArmSkin : PartLabel::LeftArmSkin;
    const PartLabel hand_label = right ? PartLabel::RightHand : PartLabel::LeftHand;

    if (person.long_sleeves) {
      // Long sleeves: the shirt down to the wrist, then only the hand is bare.
      limb(PartLabel::Sleeve, shirt, arm->shoulder, arm->elbow, d.upper_arm_half * 1.15, d.forearm_half * 1.25);
      limb(PartLabel::Sleeve, shirt, arm->elbow, arm->wrist, d.forearm_half * 1.25, d.forearm_half * 1.05);
      alpha.setTo(0);
      ellipse(alpha, ph, pt - pw, hand_len, hand_w, cv::Scalar(255), cv::LINE_AA);
      blend_skin(img, alpha, bounds({pw, ph, pt}, hand_len + 2.0, img.size()));
      if (labels) ellipse(*labels, ph, pt - pw, hand_len, hand_w, cv::Scalar(double(hand_label)), cv::LINE_8);
      continue;
    }
    alpha.setTo(0);
    capsule(alpha, ps, pe, r_up * 0.95, r_el, cv::Scalar(255), cv::LINE_AA);
    capsule(alpha, pe, pw, r_el, r_wr, cv::Scalar(255), cv::LINE_AA);
    ellipse(alpha, ph, pt - pw, hand_len, hand_w, cv::Scalar(255), cv::LINE_AA);
    const cv::Rect roi = bounds({ps, pe, pw, ph, pt}, std::max({r_up, r_el, hand_len}) + 2.0, img.size());
    blend_skin(img, alpha, roi);
    if (labels) {
      capsule(*labels, ps, pe, r_up * 0.95, r_el, cv::Scalar(double(skin_label)), cv::LINE_8);
      capsule(*labels, pe, pw, r_el, r_wr, cv::Scalar(double(skin_label)), cv::LINE_8);
      ellipse(*labels, ph, pt - pw, hand_len, hand_w, cv::Scalar(double(hand_label)), cv::LINE_8);
    }
    limb(PartLabel::Sleeve, shirt, arm->shoulder, sleeve_end, d.upper_arm_half * 1.15, d.upper_arm_half * 1.1);
  }
}

void SyntheticWorld::apply_nuisances(cv::Mat& img, const ScenarioState& s, int64_t frame_index) const {
  if (s.blur_px >= 1.5) {
    const int k = std::max(2, static_cast<int>(std::lround(s.blur_px)));
    cv::blur(img, img, cv::Size(k, 1), cv::Point(-1, -1), cv::BORDER_REFLECT);
  }
  if (std::fabs(s.light - 1.0) > 1e-6) img.convertTo(img, -1, s.light, 0.0);
  if (s.noise_sigma > 0.0) {
    const uint64_t h = splitmix64(seed_ ^ (static_cast<uint64_t>(frame_index) * 0x9E3779B97F4A7C15ull));
    const cv::Rect win(static_cast<int>(h % 64), static_cast<int>((h >> 8) % 64), img.cols, img.rows);
    cv::Mat wide;
    img.convertTo(wide, CV_16SC3);
    cv::addWeighted(wide, 1.0, noise_bank_(win), s.noise_sigma / 64.0, 0.0, img, CV_8U);
  }
  if (s.jpeg_quality > 0) {
    std::vector<uchar> buf;
    cv::imencode(".jpg", img, buf, {cv::IMWRITE_JPEG_QUALITY, s.jpeg_quality});
    img = cv::imdecode(buf, cv::IMREAD_COLOR);
  }
}

SyntheticFrame SyntheticWorld::render(double t_s, int64_t frame_index, const std::optional<CameraPose>& camera,
                                      cv::Mat* labels) const {
  const ScenarioState s = scenario_.state_at(t_s);
  const CameraPose cam = camera.value_or(scenario_.camera());
  const auto& person = scenario_.person();

  View v;
  const double amp = s.shake_deg * kDeg;
  const double tw = 2.0 * M_PI * t_s;
  v.yaw = cam.yaw + amp * (std::sin(1.7 * tw + shake_phase_[0]) + 0.5 * std::sin(4.3 * tw + shake_phase_[1])) / 1.5;
  v.pitch = amp * (std::sin(1.3 * tw + shake_phase_[2]) + 0.5 * std::sin(3.7 * tw + shake_phase_[3])) / 1.5;
  v.c = {cam.north, cam.east, cam.down};
  v.fwd = {std::cos(v.pitch) * std::cos(v.yaw), std::cos(v.pitch) * std::sin(v.yaw), -std::sin(v.pitch)};
  v.right = {-std::sin(v.yaw), std::cos(v.yaw), 0.0};
  v.down = v.fwd.cross(v.right);
  v.f = focal_;
  v.cx = 0.5 * params_.width;
  v.cy = 0.5 * params_.height;
  // The user watches the drone (the paper's assumption: the user faces the camera): they turn toward it.
  const double py = person.faces_camera && std::hypot(cam.north - person.north, cam.east - person.east) > 1e-6
                        ? std::atan2(cam.east - person.east, cam.north - person.north)
                        : person.facing_yaw;
  // A person frame at (north, east) facing yaw: the user's, and each bystander's (who always face the camera).
  const auto place = [](View& view, double north, double east, double yaw) {
    view.left = {std::sin(yaw), -std::cos(yaw), 0.0};
    view.up = {0.0, 0.0, -1.0};
    view.front = {std::cos(yaw), std::sin(yaw), 0.0};
    view.origin = {north, east, 0.0};
  };
  place(v, person.north, person.east, py - s.turn_deg * kDeg);  // turned to their left: anticlockwise from above

  SyntheticFrame out;
  out.bgr.create(params_.height, params_.width, CV_8UC3);
  if (labels) labels->create(params_.height, params_.width, CV_8UC1), labels->setTo(0);
  draw_background(out.bgr, v);

  const ScenarioDistractor& dz = scenario_.distractor();
  const cv::Point3d at(dz.left, dz.up, -dz.behind);
  // The distractor behind the wall's plane is drawn before the wall (hidden where the wall is).
  const bool wall = !wall_texture_.empty();
  const bool behind_wall = wall && (v.world(at) - wall_centre_).dot(wall_normal_) < 0.0;
  const auto draw_distractor = [&] {
    if (v.depth(at) > 0.1) {
      const cv::Point2d c = v.project(at);
      const double r = v.px(dz.radius, at);
      cv::Mat alpha(out.bgr.size(), CV_8UC1, cv::Scalar(0));
      cv::circle(alpha, fixed(c), static_cast<int>(std::lround(r * kOne)), cv::Scalar(255), cv::FILLED, cv::LINE_AA, kShift);
      blend_skin(out.bgr, alpha, bounds({c}, r + 2.0, out.bgr.size()));
      if (labels) cv::circle(*labels, fixed(c), static_cast<int>(std::lround(r * kOne)), cv::Scalar(double(PartLabel::Distractor)), cv::FILLED, cv::LINE_8, kShift);
    }
  };
  if (s.distractor && behind_wall) draw_distractor();
  if (wall) draw_wall(out.bgr, labels, v);
  if (s.distractor && !behind_wall) draw_distractor();

  const FigurePose pose = pose_figure(dims_, s.right_arm, s.left_arm, s.step_m);
  // A person behind the camera (the drone turned away or flew past) is not drawn, and has no boxes.
  const bool in_front = v.depth({pose.step_x, dims_.waist_y, 0.0}) > 0.3;
  // Everyone in front of the camera, drawn far to near: the user (index -1) and the bystanders.
  struct Drawn {
    double depth;
    int index;
    View view;
    FigurePose pose;
  };
  std::vector<Drawn> people;
  if (in_front) people.push_back({v.depth({pose.step_x, dims_.waist_y, 0.0}), -1, v, pose});
  const auto& bystanders = scenario_.bystanders();
  for (size_t i = 0; i < bystanders.size(); ++i) {
    const BystanderState b = bystanders[i].state_at(t_s);
    View bv = v;
    const double yaw = std::hypot(cam.north - b.north, cam.east - b.east) > 1e-6
                           ? std::atan2(cam.east - b.east, cam.north - b.north) : 0.0;
    place(bv, b.north, b.east, yaw);
    const FigurePose bp = pose_figure(dims_, b.right_arm, b.left_arm, 0.0);
    const double depth = bv.depth({0.0, dims_.waist_y, 0.0});
    if (depth > 0.3) people.push_back({depth, static_cast<int>(i), bv, bp});
  }
  std::stable_sort(people.begin(), people.end(), [](const Drawn& a, const Drawn& b) { return a.depth > b.depth; });
  for (const Drawn& p : people) {
    if (p.index < 0) {
      draw_person(out.bgr, labels, p.view, p.pose, person);
      continue;
    }
    // A bystander's parts are all labelled Bystander (drawn on a label image of their own, then copied over).
    cv::Mat own;
    if (labels) own = cv::Mat::zeros(out.bgr.size(), CV_8UC1);
    draw_person(out.bgr, labels ? &own : nullptr, p.view, p.pose, bystanders[static_cast<size_t>(p.index)].look);
    if (labels) labels->setTo(cv::Scalar(static_cast<double>(PartLabel::Bystander)), own != 0);
  }
  apply_nuisances(out.bgr, s, frame_index);

  // Ground truth.
  SyntheticTruth& t = out.truth;
  const cv::Vec3d feet = v.world({pose.step_x, 0.0, 0.0});
  t.person_position = cv::Point3f(float(feet[0]), float(feet[1]), float(feet[2]));
  t.camera = cam;
  t.gesture = s.gesture;
  if (!in_front) return out;  // boxes and hands zero, expected NONE / HOVER
  // The truth is the box the tracker's cascade finds, 1.1x the drawn face box at 2..4 m.
  const double half = 0.5 * kHaarBoxScale * dims_.face_box;
  const double face_cy = dims_.face_top - 0.5 * dims_.face_box;
  const std::vector<cv::Point2d> face = {v.project({pose.step_x - half, face_cy + half, 0.02}),
                                         v.project({pose.step_x + half, face_cy + half, 0.02}),
                                         v.project({pose.step_x + half, face_cy - half, 0.02}),
                                         v.project({pose.step_x - half, face_cy - half, 0.02})};
  double fx0 = 1e9, fy0 = 1e9, fx1 = -1e9, fy1 = -1e9;
  for (const auto& p : face) fx0 = std::min(fx0, p.x), fy0 = std::min(fy0, p.y), fx1 = std::max(fx1, p.x), fy1 = std::max(fy1, p.y);
  t.face_box = cv::Rect2f(float(fx0), float(fy0), float(fx1 - fx0), float(fy1 - fy0));
  if (s.turn_deg != 0.0) {
    // Turned, the face's plane is seen at a slant (edge-on at 90 deg): the box is the face's size where it is.
    const cv::Point3d centre(pose.step_x, face_cy, 0.02);
    const cv::Point2d c = v.project(centre);
    const double side = v.px(kHaarBoxScale * dims_.face_box, centre);
    t.face_box = cv::Rect2f(float(c.x - 0.5 * side), float(c.y - 0.5 * side), float(side), float(side));
  }
  t.user_box = cv::Rect2f(body_from_face(cv::Rect2d(t.face_box), BodyProportions{}));
  const cv::Point2d rh = v.project(pose.right.hand), lh = v.project(pose.left.hand);
  t.right_hand = cv::Point2f(float(rh.x), float(rh.y));
  t.left_hand = cv::Point2f(float(lh.x), float(lh.y));
  const auto pt = [&](const cv::Point3d& p) {
    const cv::Point2d q = v.project(p);
    return cv::Point2f(float(q.x), float(q.y));
  };
  t.right_elbow = pt(pose.right.elbow), t.left_elbow = pt(pose.left.elbow);
  t.right_wrist = pt(pose.right.wrist), t.left_wrist = pt(pose.left.wrist);
  t.hand_size = static_cast<float>(1.1 * std::max(v.px(dims_.hand_length, pose.right.hand), v.px(dims_.hand_length, pose.left.hand)));
  // p_uc and p_bc where the figure's shoulders and hips are: the arm points from the shoulders, whatever a
  // stage estimates them from (the paper: the box; the pose method: landmarks).
  const cv::Point3d shoulders = 0.5 * (pose.right.shoulder + pose.left.shoulder);
  const cv::Point3d hips(pose.step_x, dims_.hip_y, 0.0);
  const TorsoCentres centres{pt(shoulders), pt(0.5 * (shoulders + hips))};
  const ExpectedCommand e = expected_command(t.user_box, {t.right_hand, t.left_hand}, out.bgr.size(), t.hand_size, centres);
  t.shoulder_centre = e.shoulder_centre;
  t.body_centre = e.body_centre;
  t.expected_kind = e.kind;
  t.expected_vector = e.vector;
  t.expected_mode = e.mode;
  t.expected_direction = e.direction;
  if (faces_away(v, pose.step_x)) {
    // The back to the camera: no face for a cascade, and no gesture (the paper's user faces the drone: an arm
    // out with the back turned shows someone else the way).
    t.face_box = cv::Rect2f();
    t.expected_kind = 0;
    t.expected_vector = cv::Point2f();
    t.expected_mode = 0;
    t.expected_direction = cv::Point3f();
  }
  return out;
}

}  // namespace gpilot
