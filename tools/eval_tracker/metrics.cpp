// OTB scores and the success plot (see metrics.hpp).
#include "metrics.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace gpilot {

double centre_error(const cv::Rect2d& a, const cv::Rect2d& b) {
  if (a.area() <= 0) return std::numeric_limits<double>::infinity();
  return std::hypot(a.x + a.width / 2 - b.x - b.width / 2, a.y + a.height / 2 - b.y - b.height / 2);
}

TrackScores score(const std::vector<double>& ious, const std::vector<double>& errors) {
  TrackScores s;
  s.frames = static_cast<int>(ious.size());
  s.success.assign(21, 0.0);
  if (ious.empty()) return s;
  for (double v : ious) {
    s.mean_iou += v;
    for (int t = 0; t <= 20; ++t)
      if (v > t * 0.05) s.success[static_cast<size_t>(t)] += 1;
  }
  for (double e : errors)
    if (e <= 20.0) s.precision_20px += 1;
  const double n = static_cast<double>(ious.size());
  for (double& r : s.success) r /= n;
  for (double r : s.success) s.success_auc += r / 21.0;
  s.mean_iou /= n;
  s.precision_20px /= n;
  return s;
}

AbsenceBehaviour absence_behaviour(const std::vector<FrameVerdict>& frames, double refound_iou) {
  AbsenceBehaviour b;
  int waiting = -1;  // visible frames since the last reappearance not yet re-found; -1: none pending
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameVerdict& f = frames[i];
    if (f.absent) {
      ++b.absent_frames;
      if (!f.reported) ++b.reported_lost;
      if (i + 1 < frames.size() && !frames[i + 1].absent) {
        b.refound_after.push_back(-1);
        waiting = 0;
      } else {
        waiting = -1;
      }
      continue;
    }
    if (waiting < 0) continue;
    if (f.reported && f.iou >= refound_iou) {
      b.refound_after.back() = waiting;
      waiting = -1;
    } else {
      ++waiting;
    }
  }
  return b;
}

void write_success_plot(const std::string& path, const std::string& title, const std::vector<PlotCurve>& curves) {
  const int W = 720, H = 520, L = 70, R = 260, T = 50, B = 60;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto px = [&](double t, double r) {
    return cv::Point(L + static_cast<int>(t * (W - L - R)), H - B - static_cast<int>(r * (H - T - B)));
  };
  for (int i = 0; i <= 10; ++i) {
    const double v = i / 10.0;
    cv::line(img, px(v, 0), px(v, 1), cv::Scalar(225, 225, 225));
    cv::line(img, px(0, v), px(1, v), cv::Scalar(225, 225, 225));
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    cv::putText(img, buf, px(v, 0) + cv::Point(-10, 20), cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
    cv::putText(img, buf, px(0, v) + cv::Point(-35, 5), cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
  }
  cv::rectangle(img, px(0, 1), px(1, 0), cv::Scalar(0, 0, 0));
  cv::putText(img, "IoU threshold", cv::Point(L + 150, H - 15), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
  cv::putText(img, "success rate", cv::Point(5, T - 15), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
  cv::putText(img, title, cv::Point(L + 120, 25), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1);
  const cv::Scalar colours[] = {{0, 0, 220}, {200, 0, 0}, {0, 150, 0}, {0, 140, 255}, {160, 0, 160}, {120, 120, 0}, {60, 60, 60}};
  for (size_t c = 0; c < curves.size(); ++c) {
    const cv::Scalar col = colours[c % (sizeof colours / sizeof colours[0])];
    const auto& s = curves[c].success;
    for (size_t i = 1; i < s.size(); ++i)
      cv::line(img, px((i - 1) / 20.0, s[i - 1]), px(i / 20.0, s[i]), col, 2, cv::LINE_AA);
    cv::putText(img, curves[c].label, cv::Point(W - R + 15, T + 20 + 22 * static_cast<int>(c)), cv::FONT_HERSHEY_SIMPLEX,
                0.45, col, 1, cv::LINE_AA);
  }
  if (!cv::imwrite(path, img)) throw std::runtime_error(path + ": cannot write the success plot");
}

}  // namespace gpilot
