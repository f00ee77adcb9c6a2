#include "overlay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace gpilot {
namespace {

const cv::Scalar kHudBackground(32, 32, 32);
const cv::Scalar kHudText(235, 235, 235);
const cv::Scalar kSkeletonColour(255, 255, 0);  // cyan: apart from the paper's red marks and the truth's green
// Landmarks the model thinks hidden below this are not drawn (where BlazePose itself stops drawing them).
constexpr float kSkeletonMinVisibility = 0.5f;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

std::string fmt(const char* f, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}

std::string fmt2(const char* f, double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

double font_scale(const cv::Size& s) { return std::clamp(s.width / 1000.0, 0.35, 0.6); }
int mark_thickness(const cv::Size& s) { return std::max(2, static_cast<int>(std::lround(s.width / 320.0))); }
cv::Rect to_rect(const float* b) {
  return cv::Rect(static_cast<int>(std::lround(b[0])), static_cast<int>(std::lround(b[1])),
                  static_cast<int>(std::lround(b[2])), static_cast<int>(std::lround(b[3])));
}
cv::Point to_point(const cv::Point2f& p) {
  return cv::Point(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
}

// HUD items flowed into lines that fit the strip's width.
std::vector<std::string> flow(const std::vector<std::string>& items, int width, double scale) {
  std::vector<std::string> lines;
  std::string line;
  for (const auto& item : items) {
    const std::string candidate = line.empty() ? item : line + "   " + item;
    int base = 0;
    if (!line.empty() && cv::getTextSize(candidate, kFont, scale, 1, &base).width > width - 12) {
      lines.push_back(line);
      line = item;
    } else {
      line = candidate;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::vector<std::string> hud_items(int64_t seq, const FrameMessages& m, const HudState& hud,
                                   const OverlayOptions& options) {
  std::vector<std::string> items;
  items.push_back("seq " + std::to_string(seq));
  if (m.cmd) {
    const auto& c = *m.cmd;
    std::string mode = std::string("mode ") + mode_name(c.mode);
    if (c.mode == gesture_cmd_t::MODE_FINE || c.mode == gesture_cmd_t::MODE_UP || c.mode == gesture_cmd_t::MODE_DOWN)
      mode += fmt2(" (%+.2f,%+.2f)", c.direction[0], c.direction[1]);
    items.push_back(mode);
    items.push_back("buf " + std::to_string(c.buffer_fill) + " out " + std::to_string(c.n_out) + " hi " +
                    std::to_string(c.n_front_higher) + " lo " + std::to_string(c.n_front_lower));
  } else {
    items.push_back("mode -");
  }
  if (m.track) {
    const auto& t = *m.track;
    items.push_back(std::string("track ") + track_status_name(t.status) + " id " + std::to_string(t.track_id) +
                    fmt(" conf %.1f", t.confidence));
  } else {
    items.push_back("track -");
  }
  if (m.hand) {
    const auto& h = *m.hand;
    const char* kind = h.kind == hand_obs_t::KIND_OUT ? "OUT" : h.kind == hand_obs_t::KIND_FRONT ? "FRONT" : "none";
    std::string s = std::string("hand ") + kind;
    if (h.kind != hand_obs_t::KIND_NONE) s += fmt2(" (%+.0f,%+.0f)", h.vector[0], h.vector[1]);
    items.push_back(s);
    if (options.skin)
      items.push_back("skin out " + std::to_string(h.skin_outside) + " in " + std::to_string(h.skin_inside) +
                      " hand " + std::to_string(h.hand_skin));
  }
  if (hud.vehicle) {
    const auto& v = *hud.vehicle;
    items.push_back(fmt2("N %+.2f E %+.2f", v.position[0], v.position[1]) + fmt(" alt %.2f m", -v.position[2]) +
                    fmt(" yaw %+.0f deg", v.attitude[2] * 180.0 / M_PI));
  } else {
    items.push_back("vehicle -");
  }
  if (hud.setpoint) items.push_back(hud.setpoint->engaged ? "ENGAGED" : "not engaged");
  if (!hud.stage_hz.empty()) {
    std::string s = "Hz";
    for (const auto& [name, hz] : hud.stage_hz) {
      const std::string shortname = name.rfind("gpilot-", 0) == 0 ? name.substr(7) : name;
      s += " " + shortname + fmt(" %.1f", hz);
    }
    items.push_back(s);
  }
  if (options.truth && m.truth) {
    std::string s = std::string("truth ") + mode_name(m.truth->expected_mode);
    if (m.cmd) s += m.cmd->mode == m.truth->expected_mode ? " ok" : " MISMATCH";
    items.push_back(s);
  }
  return items;
}

// The body landmarks of a HAND_OBS (pose method): the bones between landmarks seen with at least
// kSkeletonMinVisibility, and a dot on each such joint.
void draw_skeleton(cv::Mat& img, const hand_obs_t& h) {
  const auto seen = [&](int i) { return h.pose_landmarks[i][3] >= kSkeletonMinVisibility; };
  const auto at = [&](int i) { return cv::Point(static_cast<int>(std::lround(h.pose_landmarks[i][0])), static_cast<int>(std::lround(h.pose_landmarks[i][1]))); };
  for (const auto& [a, b] : pose_landmark::kBones)
    if (seen(a) && seen(b)) cv::line(img, at(a), at(b), kSkeletonColour, 1, cv::LINE_AA);
  for (int i = pose_landmark::kLeftShoulder; i < kPoseLandmarkCount; ++i)
    if (seen(i)) cv::circle(img, at(i), 2, kSkeletonColour, cv::FILLED, cv::LINE_AA);
}

void draw_truth(cv::Mat& img, const ground_truth_t& t) {
  cv::rectangle(img, to_rect(t.user_box), kTruthGreen, 1, cv::LINE_8);
  const int r = std::max(3, static_cast<int>(t.hand_size / 2));
  cv::circle(img, to_point({t.left_hand[0], t.left_hand[1]}), r, kTruthGreen, 1, cv::LINE_8);
  cv::circle(img, to_point({t.right_hand[0], t.right_hand[1]}), r, kTruthGreen, 1, cv::LINE_8);
  cv::drawMarker(img, to_point({t.shoulder_centre[0], t.shoulder_centre[1]}), kTruthGreen, cv::MARKER_DIAMOND, 8, 1);
}

void draw_skin(cv::Mat& img, const cv::Mat& frame, const FrameMessages& m, const OverlayOptions& o) {
  if (!o.skin_mask) return;
  const cv::Mat mask = o.skin_mask(frame, m);
  if (mask.empty() || mask.size() != frame.size() || mask.type() != CV_8UC1) return;
  cv::Mat tinted = img.clone();
  tinted.setTo(cv::Scalar(255, 0, 255), mask);
  cv::addWeighted(img, 0.5, tinted, 0.5, 0.0, img);
}

}  // namespace

const char* mode_name(int mode) {
  switch (mode) {
    case gesture_cmd_t::MODE_HOVER: return "HOVER";
    case gesture_cmd_t::MODE_FINE: return "FINE";
    case gesture_cmd_t::MODE_UP: return "UP";
    case gesture_cmd_t::MODE_DOWN: return "DOWN";
    case gesture_cmd_t::MODE_CLOSER: return "CLOSER";
    case gesture_cmd_t::MODE_FURTHER: return "FURTHER";
    default: return "?";
  }
}

const char* track_status_name(int status) {
  switch (status) {
    case user_track_t::STATUS_SEARCHING: return "SEARCHING";
    case user_track_t::STATUS_TRACKING: return "TRACKING";
    case user_track_t::STATUS_LOST: return "LOST";
    default: return "?";
  }
}

std::optional<CommandMark> command_mark(const FrameMessages& m) {
  if (!m.cmd || !m.hand) return std::nullopt;
  const auto& c = *m.cmd;
  const auto& h = *m.hand;
  CommandMark mark;
  mark.mode = c.mode;
  mark.origin = {h.shoulder_centre[0], h.shoulder_centre[1]};
  // The command's vector is the mean hand vector divided by the box width it was measured with.
  const float w = c.user_box_width > 0 ? c.user_box_width : h.user_box[2];
  mark.tip = mark.origin + cv::Point2f(c.direction[0] * w, c.direction[1] * w);
  switch (c.mode) {
    case gesture_cmd_t::MODE_CLOSER: mark.size = std::max(5.0f, h.user_box[2] / 8.0f); break;
    case gesture_cmd_t::MODE_FURTHER: mark.size = std::max(4.0f, h.user_box[2] / 12.0f); break;
    default: mark.size = 0; break;
  }
  return mark;
}

int hud_height(const cv::Size& frame, const OverlayOptions& options) {
  if (!options.hud) return 0;
  // Worst case for the flowed text (the strip keeps one height through a video): every item present.
  FrameMessages all;
  all.cmd = gesture_cmd_t{};
  all.track = user_track_t{};
  all.hand = hand_obs_t{};
  all.hand->kind = hand_obs_t::KIND_OUT;
  all.truth = ground_truth_t{};
  HudState hud;
  hud.vehicle = vehicle_state_t{};
  hud.setpoint = flight_setpoint_t{};
  for (const char* n : {"gpilot-capture", "gpilot-tracker", "gpilot-hands", "gpilot-decide", "gpilot-flight"})
    hud.stage_hz[n] = 100.0f;
  const OverlayOptions& o = options;
  const double scale = font_scale(frame);
  int base = 0;
  const int line_h = static_cast<int>(cv::getTextSize("Ag", kFont, scale, 1, &base).height * 1.8) + 2;
  const auto lines = flow(hud_items(-1000000, all, hud, o), frame.width, scale);
  return static_cast<int>(lines.size()) * line_h + line_h / 2;
}

cv::Mat draw_overlay(const cv::Mat& frame, int64_t seq, const FrameMessages& m, const HudState& hud,
                     const OverlayOptions& options) {
  CV_Assert(!frame.empty() && (frame.type() == CV_8UC3 || frame.type() == CV_8UC1));
  const int strip = hud_height(frame.size(), options);
  cv::Mat out(frame.rows + strip, frame.cols, CV_8UC3, kHudBackground);
  cv::Mat img = out(cv::Rect(0, 0, frame.cols, frame.rows));
  if (frame.type() == CV_8UC1)
    cv::cvtColor(frame, img, cv::COLOR_GRAY2BGR);
  else
    frame.copyTo(img);

  const int t = mark_thickness(frame.size());
  const double scale = font_scale(frame.size());
  if (options.skin) draw_skin(img, frame, m, options);
  if (options.truth && m.truth) draw_truth(img, *m.truth);

  // User box: the track's box when tracking (or the last good one, amber, when lost).
  if (m.track && m.track->status != user_track_t::STATUS_SEARCHING) {
    const bool lost = m.track->status == user_track_t::STATUS_LOST;
    const cv::Rect box = to_rect(m.track->box);
    cv::rectangle(img, box, lost ? kLostAmber : kMarkRed, t, cv::LINE_8);
    std::string label = lost ? "LOST" : (m.cmd ? mode_name(m.cmd->mode) : "");
    if (!lost && m.track->facing == user_track_t::FACING_AWAY) label += label.empty() ? "TURNED AWAY" : " (turned away)";
    if (!label.empty())
      cv::putText(img, label, cv::Point(box.x + t, std::max(12, box.y - 2 * t)), kFont, scale,
                  lost ? kLostAmber : kMarkRed, 1, cv::LINE_AA);
  } else if (m.track) {
    cv::putText(img, "searching for a face", cv::Point(8, 8 + static_cast<int>(24 * scale)), kFont, scale, kLostAmber,
                1, cv::LINE_AA);
  }

  // The face the tracker's cascade found in this frame (start of a track, re-checks), thin.
  if (m.track && m.track->face_box[2] > 0 && m.track->face_box[3] > 0)
    cv::rectangle(img, to_rect(m.track->face_box), kMarkRed, 1, cv::LINE_8);

  // The user's body (pose method): thin, under the paper's marks.
  if (m.hand && m.hand->method == hand_obs_t::METHOD_POSE && m.hand->pose_score > 0) draw_skeleton(img, *m.hand);

  // Hand square.
  if (m.hand && m.hand->kind != hand_obs_t::KIND_NONE) {
    cv::rectangle(img, to_rect(m.hand->hand_box), kMarkRed, t, cv::LINE_8);
    if (options.skin)
      cv::putText(img, std::to_string(m.hand->hand_skin),
                  cv::Point(static_cast<int>(m.hand->hand_box[0]),
                            static_cast<int>(m.hand->hand_box[1] + m.hand->hand_box[3]) + static_cast<int>(20 * scale)),
                  kFont, scale, kMarkRed, 1, cv::LINE_AA);
  }

  // The command, from p_uc.
  if (const auto mark = command_mark(m)) {
    const cv::Point o = to_point(mark->origin);
    switch (mark->mode) {
      case gesture_cmd_t::MODE_FINE:
      case gesture_cmd_t::MODE_UP:
      case gesture_cmd_t::MODE_DOWN: {
        const cv::Point tip = to_point(mark->tip);
        const double len = cv::norm(tip - o);
        if (len >= 1.0) cv::arrowedLine(img, o, tip, kMarkRed, t, cv::LINE_8, 0, std::min(0.3, 12.0 / len));
        break;
      }
      case gesture_cmd_t::MODE_CLOSER: {
        const int s = static_cast<int>(std::lround(mark->size));
        cv::line(img, o + cv::Point(-s, -s), o + cv::Point(s, s), kMarkRed, t, cv::LINE_8);
        cv::line(img, o + cv::Point(-s, s), o + cv::Point(s, -s), kMarkRed, t, cv::LINE_8);
        break;
      }
      case gesture_cmd_t::MODE_FURTHER:
        cv::circle(img, o, static_cast<int>(std::lround(mark->size)), kMarkRed, t, cv::LINE_8);
        break;
      default: break;
    }
  }

  if (strip > 0) {
    int base = 0;
    const int line_h = static_cast<int>(cv::getTextSize("Ag", kFont, scale, 1, &base).height * 1.8) + 2;
    int y = frame.rows + line_h;
    for (const auto& line : flow(hud_items(seq, m, hud, options), frame.cols, scale)) {
      cv::putText(out, line, cv::Point(6, y - line_h / 4), kFont, scale, kHudText, 1, cv::LINE_AA);
      y += line_h;
    }
  }
  return out;
}

void BoxDrag::press(int x, int y) {
  active_ = true;
  a_ = b_ = cv::Point(x, y);
}

void BoxDrag::move(int x, int y) {
  if (active_) b_ = cv::Point(x, y);
}

cv::Rect BoxDrag::current() const { return cv::Rect(a_, b_); }

std::optional<cv::Rect> BoxDrag::release(int x, int y, const cv::Size& bounds) {
  if (!active_) return std::nullopt;
  active_ = false;
  b_ = cv::Point(x, y);
  const cv::Rect box = cv::Rect(a_, b_) & cv::Rect(cv::Point(0, 0), bounds);
  if (box.width < 4 || box.height < 4) return std::nullopt;
  return box;
}

}  // namespace gpilot
