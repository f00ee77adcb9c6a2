#include "trajectory_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "overlay.hpp"

namespace gpilot {
namespace {

const cv::Size kCanvas(1500, 960);
const cv::Rect kTopPanel(90, 120, 700, 780);      // plotting areas (inside the axes)
const cv::Rect kAltPanel(900, 120, 570, 330);
const cv::Rect kDistPanel(900, 570, 570, 330);
const cv::Scalar kInk(30, 30, 30);
const cv::Scalar kGrid(225, 225, 225);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

struct Axes {
  cv::Rect area;
  double x0, x1, y0, y1;
  cv::Point map(double x, double y) const {
    return cv::Point(area.x + static_cast<int>(std::lround((x - x0) / (x1 - x0) * area.width)),
                     area.y + area.height - static_cast<int>(std::lround((y - y0) / (y1 - y0) * area.height)));
  }
};

std::string tick_label(double v, double step) {
  char buf[32];
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buf;
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, const cv::Scalar& c = kInk, int thick = 1) {
  cv::putText(img, s, at, kFont, scale, c, thick, cv::LINE_AA);
}

void centred(cv::Mat& img, const std::string& s, cv::Point centre, double scale, int thick = 1) {
  int base = 0;
  const cv::Size sz = cv::getTextSize(s, kFont, scale, thick, &base);
  text(img, s, cv::Point(centre.x - sz.width / 2, centre.y + sz.height / 2), scale, kInk, thick);
}

// Text turned 90 degrees counter-clockwise, centred at centre (a y-axis label).
void vertical(cv::Mat& img, const std::string& s, cv::Point centre, double scale) {
  int base = 0;
  const cv::Size sz = cv::getTextSize(s, kFont, scale, 1, &base);
  cv::Mat patch(sz.height + base + 4, sz.width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
  text(patch, s, cv::Point(2, sz.height + 2), scale);
  cv::Mat turned;
  cv::rotate(patch, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect dst(centre.x - turned.cols / 2, centre.y - turned.rows / 2, turned.cols, turned.rows);
  if ((dst & cv::Rect(0, 0, img.cols, img.rows)) == dst) turned.copyTo(img(dst));
}

void draw_axes(cv::Mat& img, const Axes& ax, const std::string& title, const std::string& xlabel,
               const std::string& ylabel) {
  const auto xt = nice_ticks(ax.x0, ax.x1, 7);
  const auto yt = nice_ticks(ax.y0, ax.y1, 6);
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double x : xt) {
    const cv::Point p = ax.map(x, ax.y0);
    cv::line(img, cv::Point(p.x, ax.area.y), cv::Point(p.x, ax.area.y + ax.area.height), kGrid, 1);
    cv::line(img, cv::Point(p.x, p.y), cv::Point(p.x, p.y + 6), kInk, 1);
    centred(img, tick_label(x, xstep), cv::Point(p.x, p.y + 20), 0.45);
  }
  for (double y : yt) {
    const cv::Point p = ax.map(ax.x0, y);
    cv::line(img, cv::Point(ax.area.x, p.y), cv::Point(ax.area.x + ax.area.width, p.y), kGrid, 1);
    cv::line(img, cv::Point(p.x - 6, p.y), p, kInk, 1);
    const std::string l = tick_label(y, ystep);
    int base = 0;
    const cv::Size sz = cv::getTextSize(l, kFont, 0.45, 1, &base);
    text(img, l, cv::Point(p.x - 10 - sz.width, p.y + sz.height / 2), 0.45);
  }
  cv::rectangle(img, ax.area, kInk, 1);
  centred(img, title, cv::Point(ax.area.x + ax.area.width / 2, ax.area.y - 18), 0.6, 2);
  centred(img, xlabel, cv::Point(ax.area.x + ax.area.width / 2, ax.area.y + ax.area.height + 45), 0.5);
  vertical(img, ylabel, cv::Point(ax.area.x - 62, ax.area.y + ax.area.height / 2), 0.5);
}

// [lo, hi] widened by a margin, never empty.
std::pair<double, double> padded(double lo, double hi, double min_span) {
  if (hi - lo < min_span) {
    const double c = 0.5 * (lo + hi);
    lo = c - min_span / 2;
    hi = c + min_span / 2;
  }
  const double m = 0.06 * (hi - lo);
  return {lo - m, hi + m};
}

void draw_path(cv::Mat& img, const Axes& ax, const std::vector<TrajectoryPoint>& path,
               double (*x)(const TrajectoryPoint&), double (*y)(const TrajectoryPoint&)) {
  cv::Mat clip = img(ax.area);  // keep the path inside the axes
  const cv::Point off(ax.area.x, ax.area.y);
  for (size_t i = 1; i < path.size(); ++i)
    cv::line(clip, ax.map(x(path[i - 1]), y(path[i - 1])) - off, ax.map(x(path[i]), y(path[i])) - off,
             mode_colour(path[i].mode), 3, cv::LINE_AA);
  if (path.size() == 1) cv::circle(clip, ax.map(x(path[0]), y(path[0])) - off, 3, mode_colour(path[0].mode), cv::FILLED);
}

void user_marker(cv::Mat& img, cv::Point p) {
  const std::vector<cv::Point> tri{p + cv::Point(0, -11), p + cv::Point(-10, 8), p + cv::Point(10, 8)};
  cv::fillConvexPoly(img, tri, kInk, cv::LINE_AA);
}

void legend(cv::Mat& img, bool has_person) {
  int x = 90;
  const int y = 78;
  auto item = [&](const std::string& label, const cv::Scalar& c) {
    cv::line(img, cv::Point(x, y), cv::Point(x + 34, y), c, 4, cv::LINE_AA);
    text(img, label, cv::Point(x + 42, y + 6), 0.5);
    int base = 0;
    x += 42 + cv::getTextSize(label, kFont, 0.5, 1, &base).width + 26;
  };
  item("no command yet", mode_colour(-1));
  for (int m = 0; m < kModes; ++m) item(mode_name(m), mode_colour(m));
  x += 10;
  cv::circle(img, cv::Point(x + 8, y), 7, kInk, 2, cv::LINE_AA);
  text(img, "start", cv::Point(x + 22, y + 6), 0.5);
  x += 90;
  cv::rectangle(img, cv::Rect(x + 1, y - 7, 14, 14), kInk, cv::FILLED);
  text(img, "end", cv::Point(x + 22, y + 6), 0.5);
  x += 80;
  if (has_person) {
    user_marker(img, cv::Point(x + 8, y));
    text(img, "user", cv::Point(x + 22, y + 6), 0.5);
  }
}

double horizontal_distance(const TrajectoryPoint& p) {
  return std::hypot(p.north - p.person_north, p.east - p.person_east);
}

}  // namespace

cv::Scalar mode_colour(int mode) {
  switch (mode) {
    case gesture_cmd_t::MODE_HOVER: return {110, 110, 110};
    case gesture_cmd_t::MODE_FINE: return {0, 140, 255};
    case gesture_cmd_t::MODE_UP: return {40, 170, 40};
    case gesture_cmd_t::MODE_DOWN: return {200, 110, 0};
    case gesture_cmd_t::MODE_CLOSER: return {190, 90, 240};
    case gesture_cmd_t::MODE_FURTHER: return {130, 30, 110};
    default: return {205, 205, 205};
  }
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> out;
  if (!(hi > lo) || target < 1) return out;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) out.push_back(v);
  return out;
}

cv::Point TopViewMapping::map(double north, double east) const {
  return Axes{area, east0, east1, north0, north1}.map(east, north);
}

TopViewMapping top_view_mapping(const std::vector<TrajectoryPoint>& path) {
  double e0 = 0, e1 = 0, n0 = 0, n1 = 0;
  bool any = false;
  auto take = [&](double n, double e) {
    if (!any) {
      e0 = e1 = e;
      n0 = n1 = n;
      any = true;
    }
    e0 = std::min(e0, e), e1 = std::max(e1, e), n0 = std::min(n0, n), n1 = std::max(n1, n);
  };
  for (const auto& p : path) {
    take(p.north, p.east);
    if (p.has_person) take(p.person_north, p.person_east);
  }
  auto [ea, eb] = padded(e0, e1, 2.0);
  auto [na, nb] = padded(n0, n1, 2.0);
  // Equal scale: widen the shorter side to the panel's aspect ratio.
  const double mpp = std::max((eb - ea) / kTopPanel.width, (nb - na) / kTopPanel.height);
  const double ec = 0.5 * (ea + eb), nc = 0.5 * (na + nb);
  return TopViewMapping{kTopPanel, ec - mpp * kTopPanel.width / 2, ec + mpp * kTopPanel.width / 2,
                        nc - mpp * kTopPanel.height / 2, nc + mpp * kTopPanel.height / 2};
}

cv::Mat draw_trajectory(const std::vector<TrajectoryPoint>& path, const std::string& title) {
  cv::Mat img(kCanvas, CV_8UC3, cv::Scalar(255, 255, 255));
  text(img, title, cv::Point(90, 36), 0.75, kInk, 2);
  const bool has_person = std::any_of(path.begin(), path.end(), [](const TrajectoryPoint& p) { return p.has_person; });
  legend(img, has_person);

  // Top view.
  const TopViewMapping tv = top_view_mapping(path);
  const Axes top{tv.area, tv.east0, tv.east1, tv.north0, tv.north1};
  draw_axes(img, top, "seen from above (north up)", "east (m)", "north (m)");
  draw_path(img, top, path, [](const TrajectoryPoint& p) { return p.east; }, [](const TrajectoryPoint& p) { return p.north; });
  if (!path.empty()) {
    cv::circle(img, top.map(path.front().east, path.front().north), 7, kInk, 2, cv::LINE_AA);
    const auto& last = path.back();
    const cv::Point end = top.map(last.east, last.north);
    cv::rectangle(img, cv::Rect(end.x - 7, end.y - 7, 14, 14), kInk, cv::FILLED);
    // Heading: yaw 0 is north, positive clockwise seen from above.
    cv::arrowedLine(img, end, end + cv::Point(static_cast<int>(std::lround(30 * std::sin(last.yaw))),
                                              static_cast<int>(std::lround(-30 * std::cos(last.yaw)))),
                    kInk, 2, cv::LINE_AA, 0, 0.35);
    if (last.has_person) {
      const cv::Point u = top.map(last.person_east, last.person_north);
      user_marker(img, u);
      text(img, "user", u + cv::Point(12, 18), 0.5);
    }
  } else {
    centred(img, "no VEHICLE_STATE in the log", cv::Point(kTopPanel.x + kTopPanel.width / 2, kTopPanel.y + kTopPanel.height / 2), 0.7, 2);
  }

  // Altitude and distance against time.
  double t1 = path.empty() ? 1.0 : path.back().t_s;
  double a0 = 0, a1 = 0, d0 = 0, d1 = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    const double alt = -path[i].down;
    const double dist = has_person ? (path[i].has_person ? horizontal_distance(path[i]) : 0.0)
                                   : std::hypot(path[i].north - path[0].north, path[i].east - path[0].east);
    a0 = i ? std::min(a0, alt) : alt, a1 = i ? std::max(a1, alt) : alt;
    d0 = i ? std::min(d0, dist) : dist, d1 = i ? std::max(d1, dist) : dist;
  }
  const auto [ta, tb] = padded(0.0, std::max(t1, 1e-3), 1.0);
  const auto [aa, ab] = padded(a0, a1, 1.0);
  const auto [da, db] = padded(d0, d1, 1.0);
  const Axes alt{kAltPanel, ta, tb, aa, ab};
  draw_axes(img, alt, "altitude", "time (s)", "altitude (m)");
  draw_path(img, alt, path, [](const TrajectoryPoint& p) { return p.t_s; }, [](const TrajectoryPoint& p) { return -p.down; });
  const Axes dist{kDistPanel, ta, tb, da, db};
  if (has_person) {
    draw_axes(img, dist, "horizontal distance to the user", "time (s)", "distance (m)");
    std::vector<TrajectoryPoint> with_person;
    for (const auto& p : path)
      if (p.has_person) with_person.push_back(p);
    draw_path(img, dist, with_person, [](const TrajectoryPoint& p) { return p.t_s; }, horizontal_distance);
  } else {
    draw_axes(img, dist, "horizontal distance from the start (no GROUND_TRUTH)", "time (s)", "distance (m)");
    std::vector<TrajectoryPoint> rel = path;
    for (auto& p : rel) {
      p.person_north = path.front().north;
      p.person_east = path.front().east;
    }
    draw_path(img, dist, rel, [](const TrajectoryPoint& p) { return p.t_s; }, horizontal_distance);
  }
  return img;
}

}  // namespace gpilot
