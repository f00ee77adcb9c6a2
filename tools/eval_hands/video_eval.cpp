#include "video_eval.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <vector>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "capture/frame_sources.hpp"
#include "capture/scenario.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "decide/decide_service.hpp"
#include "hands/hands_core_factory.hpp"
#include "hands/hands_params.hpp"
#include "hands/hands_service.hpp"
#include "image_codec.hpp"
#include "image_codec_params.hpp"
#include "overlay.hpp"
#include "tracker/face_cascade.hpp"
#include "tracker/tracker_params.hpp"
#include "tracker/tracker_service.hpp"
#include "video_sink.hpp"

namespace gpilot {
namespace {

cv::Rect2d parse_init_box(const std::string& text) {
  std::array<double, 4> v{};
  std::istringstream in(text);
  char sep = 0;
  if (!(in >> v[0] >> sep >> v[1] >> sep >> v[2] >> sep >> v[3]) || !std::isfinite(v[0] + v[1] + v[2] + v[3]) ||
      v[2] <= 0 || v[3] <= 0)
    throw std::runtime_error("--init-box '" + text + "': want x,y,w,h in pixels, w and h > 0");
  return {v[0], v[1], v[2], v[3]};
}

std::unique_ptr<FrameSource> open_source(const VideoEvalOptions& o) {
  if (std::filesystem::is_directory(o.source)) return std::make_unique<ImageFolderSource>(o.source, o.fps, false);
  return std::make_unique<VideoFileSource>(o.source, false);
}

struct TruthRange {
  int64_t first = 0, last = 0;
  int gesture = ground_truth_t::GESTURE_REST;
};

std::vector<TruthRange> read_truth(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("--truth " + path + ": cannot read it");
  std::vector<TruthRange> ranges;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string a, b, g;
    TruthRange r;
    try {
      if (!std::getline(fields, a, ',') || !std::getline(fields, b, ',') || !std::getline(fields, g)) throw std::invalid_argument(line);
      size_t used_a = 0, used_b = 0;
      r.first = std::stoll(a, &used_a);
      r.last = std::stoll(b, &used_b);
      if (used_a != a.size() || used_b != b.size() || r.first < 0 || r.last < r.first) throw std::invalid_argument(line);
      r.gesture = gesture_from_name(g);
    } catch (const std::exception&) {
      throw std::runtime_error("--truth " + path + " line " + std::to_string(n) + ": want first,last,GESTURE (0-based frames, "
                               "first <= last; GESTURE one of REST OUT UP DOWN CLOSER FURTHER), got '" + line + "'");
    }
    ranges.push_back(r);
  }
  if (ranges.empty()) throw std::runtime_error("--truth " + path + ": no range in it");
  return ranges;
}

std::optional<int> gesture_at(const std::vector<TruthRange>& ranges, int64_t frame) {
  for (const auto& r : ranges)
    if (frame >= r.first && frame <= r.last) return r.gesture;
  return std::nullopt;
}

// What the stage should see and decide for a gesture (as the synthetic world's truth: truth_rules).
int8_t expected_kind(int gesture) {
  switch (gesture) {
    case ground_truth_t::GESTURE_OUT:
    case ground_truth_t::GESTURE_UP:
    case ground_truth_t::GESTURE_DOWN: return hand_obs_t::KIND_OUT;
    case ground_truth_t::GESTURE_CLOSER:
    case ground_truth_t::GESTURE_FURTHER: return hand_obs_t::KIND_FRONT;
    default: return hand_obs_t::KIND_NONE;
  }
}

int8_t expected_mode(int gesture) {
  switch (gesture) {
    case ground_truth_t::GESTURE_OUT: return gesture_cmd_t::MODE_FINE;
    case ground_truth_t::GESTURE_UP: return gesture_cmd_t::MODE_UP;
    case ground_truth_t::GESTURE_DOWN: return gesture_cmd_t::MODE_DOWN;
    case ground_truth_t::GESTURE_CLOSER: return gesture_cmd_t::MODE_CLOSER;
    case ground_truth_t::GESTURE_FURTHER: return gesture_cmd_t::MODE_FURTHER;
    default: return gesture_cmd_t::MODE_HOVER;
  }
}

struct GestureScore {
  int64_t judged = 0, hand_right = 0, command_right = 0, moving = 0;
};

// HAND_OBS's kind by the stage's own names (HandKind has hand_obs_t::KIND_*'s values).
const char* kind_name(int8_t k) { return hand_kind_name(static_cast<HandKind>(k)); }

}  // namespace

int run_video_eval(const VideoEvalOptions& o, const Config& config) {
  if (o.truth_path.empty() && o.gesture != "none") throw std::runtime_error("--gesture '" + o.gesture + "': only 'none' is known");
  const std::vector<TruthRange> truth =
      o.truth_path.empty() ? std::vector<TruthRange>{{0, std::numeric_limits<int64_t>::max(), ground_truth_t::GESTURE_REST}}
                           : read_truth(o.truth_path);
  auto source = open_source(o);
  const double fps = source->fps() > 0 ? source->fps() : o.fps;
  const auto tracker_params = config.section<TrackerParams>("tracker");
  UserTracker tracker(tracker_params, load_tracker_models(tracker_params));
  if (!o.init_box.empty()) {
    const std::string why = tracker.set_box(parse_init_box(o.init_box));
    if (!why.empty()) throw std::runtime_error("--init-box: " + why);
  }
  const auto hands = config.section<HandsParams>("hands");
  const auto method = make_hand_method(hands);
  GestureDecider decider(config.section<DecideParams>("decide"));
  const auto limits = config.section<ImageLimits>("image");

  std::ofstream csv;
  if (!o.csv_path.empty()) {
    csv.open(o.csv_path);
    if (!csv) throw std::runtime_error("cannot write " + o.csv_path);
    csv << "frame,truth_gesture,judged,track_status,box_x,box_y,box_w,box_h,face,hand_kind,vector_x,vector_y,hand_skin,skin_outside,skin_inside,"
           "mode,n_out,n_front_higher,n_front_lower,rejected\n";
  }
  std::unique_ptr<VideoSink> sink;
  if (!o.mp4_path.empty()) sink = std::make_unique<VideoSink>(o.mp4_path, fps, "", 0);
  OverlayOptions overlay;
  overlay.skin = true;

  int64_t frames = 0, tracking = 0, decided = 0, moving = 0, rejected = 0, faces = 0, tracks_started = 0;
  std::map<std::string, int64_t> kinds, modes, rejections;
  int32_t last_track = 0;
  std::map<int, GestureScore> scores;  // by truth gesture
  std::optional<int> segment_gesture;
  int64_t segment_start = 0;
  const auto settle_frames = static_cast<int64_t>(std::ceil(o.settle_s * fps));
  cv::Mat frame;
  std::string why;
  for (;;) {
    const ReadStatus status = source->read(frame, why);
    if (status == ReadStatus::End || status == ReadStatus::Lost) break;
    if (status == ReadStatus::Skip) {
      std::fprintf(stderr, "skipped: %s\n", why.c_str());
      continue;
    }
    // The capture adapter's utime for a file: the frame's media time (1 us after 0, as live utimes are never 0).
    const int64_t seq = frames++;
    const int64_t utime = 1 + std::llround(static_cast<double>(seq) * 1e6 / fps);
    const image_t image = mat_to_image(frame, utime, seq);
    const user_track_t track = to_message(tracker.process(frame), image);
    tracking += track.status == user_track_t::STATUS_TRACKING;
    faces += track.face_box[2] > 0;
    if (track.track_id != last_track && track.track_id != 0) ++tracks_started, last_track = track.track_id;
    FrameMessages msgs;
    msgs.track = track;
    hand_obs_t obs;
    const std::string reason = hands_on_pair(*method, image, track, limits, obs);
    std::string mode;
    if (!reason.empty()) {
      ++rejected;
      ++rejections[reason.substr(0, reason.find(':'))];
    } else {
      msgs.hand = obs;
      if (obs.track_status == user_track_t::STATUS_TRACKING) ++kinds[kind_name(obs.kind)];
      const gesture_cmd_t cmd = to_message(decider.update(to_hand_observation(obs)));
      msgs.cmd = cmd;
      mode = mode_name(cmd.mode);
      ++decided;
      ++modes[mode];
      moving += cmd.mode != gesture_cmd_t::MODE_HOVER;
    }
    // Judged: frames with a truth, settle_frames or more after the start of their run of the same gesture.
    const std::optional<int> g = gesture_at(truth, seq);
    if (g != segment_gesture) segment_gesture = g, segment_start = seq;
    const bool judged = g && seq - segment_start >= settle_frames;
    if (judged) {
      GestureScore& sc = scores[*g];
      ++sc.judged;
      const bool tracked = msgs.hand && obs.track_status == user_track_t::STATUS_TRACKING;
      const int8_t kind = tracked ? obs.kind : hand_obs_t::KIND_NONE;
      bool right = kind == expected_kind(*g);
      if (right && kind == hand_obs_t::KIND_FRONT) right = (obs.vector[1] < 0) == (*g == ground_truth_t::GESTURE_CLOSER);
      sc.hand_right += right;
      const int8_t m = msgs.cmd ? msgs.cmd->mode : gesture_cmd_t::MODE_HOVER;
      sc.command_right += m == expected_mode(*g);
      sc.moving += m != gesture_cmd_t::MODE_HOVER;
    }
    if (csv) {
      csv << seq << ',' << (g ? gesture_name(*g) : "") << ',' << (judged ? 1 : 0) << ',' << track_status_name(track.status);
      for (float v : track.box) csv << ',' << v;
      csv << ',' << (track.face_box[2] > 0 ? 1 : 0);
      if (msgs.hand)
        csv << ',' << kind_name(obs.kind) << ',' << obs.vector[0] << ',' << obs.vector[1] << ',' << obs.hand_skin << ','
            << obs.skin_outside << ',' << obs.skin_inside;
      else
        csv << ",,,,,,";
      if (msgs.cmd)
        csv << ',' << mode << ',' << static_cast<int>(msgs.cmd->n_out) << ',' << static_cast<int>(msgs.cmd->n_front_higher)
            << ',' << static_cast<int>(msgs.cmd->n_front_lower);
      else
        csv << ",,,,";
      csv << ',' << '"' << reason << '"' << '\n';
    }
    if (sink) sink->write(draw_overlay(frame, seq, msgs, HudState{}, overlay), seq, utime);
    if (frames % 100 == 0) std::fprintf(stderr, "\r%lld frames", static_cast<long long>(frames));
  }
  if (frames >= 100) std::fprintf(stderr, "\n");
  if (sink) sink->close();
  if (frames == 0) throw std::runtime_error(o.source + ": no frame could be read");

  GestureScore rest, gesture;
  for (const auto& [g, sc] : scores) {
    GestureScore& to = g == ground_truth_t::GESTURE_REST ? rest : gesture;
    to.judged += sc.judged, to.hand_right += sc.hand_right, to.command_right += sc.command_right, to.moving += sc.moving;
  }
  const auto share = [](int64_t n, int64_t of) { return of ? static_cast<double>(n) / static_cast<double>(of) : 0.0; };
  if (o.json) {
    nlohmann::json per_gesture = nlohmann::json::object();
    for (const auto& [g, sc] : scores)
      per_gesture[gesture_name(g)] = {{"judged", sc.judged}, {"hand_right", sc.hand_right}, {"command_right", sc.command_right},
                                      {"moving_command", sc.moving}};
    nlohmann::json j = {{"mode", "video"},
                        {"source", o.source},
                        {"truth", o.truth_path.empty() ? "no gesture (--gesture " + o.gesture + ")" : o.truth_path},
                        {"settle_s", o.settle_s},
                        {"init", o.init_box.empty() ? "face search" : "box " + o.init_box},
                        {"fps", fps},
                        {"frames", frames},
                        {"frames_tracking", tracking},
                        {"tracks_started", tracks_started},
                        {"faces_handed_over", faces},
                        {"hand_kinds_tracking", kinds},
                        {"frames_decided", decided},
                        {"modes", modes},
                        {"moving_command_frames", moving},
                        {"frames_rejected", rejected},
                        {"rejections", rejections},
                        {"by_gesture", per_gesture},
                        {"rest_frames_judged", rest.judged},
                        {"rest_moving_command_share", share(rest.moving, rest.judged)},
                        {"rest_hand_share", share(rest.judged - rest.hand_right, rest.judged)},
                        {"gesture_frames_judged", gesture.judged},
                        {"gesture_hand_right_share", share(gesture.hand_right, gesture.judged)},
                        {"gesture_command_right_share", share(gesture.command_right, gesture.judged)}};
    std::cout << j.dump() << std::endl;
    return 0;
  }
  std::printf("%s: %lld frames at %.1f fps; truth: %s; user from %s\n\n", o.source.c_str(), static_cast<long long>(frames), fps,
              o.truth_path.empty() ? "no gesture in the whole clip" : o.truth_path.c_str(),
              o.init_box.empty() ? "the tracker's face search" : ("box " + o.init_box).c_str());
  std::printf("frames TRACKING            %lld of %lld (%lld tracks started, a face handed over on %lld frames)\n",
              static_cast<long long>(tracking), static_cast<long long>(frames), static_cast<long long>(tracks_started),
              static_cast<long long>(faces));
  std::printf("hand kinds while TRACKING  NONE %lld  OUT %lld  FRONT %lld\n", static_cast<long long>(kinds["NONE"]),
              static_cast<long long>(kinds["OUT"]), static_cast<long long>(kinds["FRONT"]));
  std::printf("commands                  ");
  for (const auto& [m, n] : modes) std::printf(" %s %lld", m.c_str(), static_cast<long long>(n));
  std::printf("\n\njudged from %.1f s after each change of gesture:\n", o.settle_s);
  std::printf("  %-8s %8s %12s %14s %10s\n", "truth", "frames", "hand right", "command right", "moving");
  for (const auto& [g, sc] : scores)
    std::printf("  %-8s %8lld %11.1f%% %13.1f%% %9.1f%%\n", gesture_name(g), static_cast<long long>(sc.judged),
                100 * share(sc.hand_right, sc.judged), 100 * share(sc.command_right, sc.judged), 100 * share(sc.moving, sc.judged));
  std::printf("no gesture: a moving command on %.1f %% of %lld frames (bar <= 20 %%), a hand on %.1f %%\n",
              100 * share(rest.moving, rest.judged), static_cast<long long>(rest.judged),
              100 * share(rest.judged - rest.hand_right, rest.judged));
  if (gesture.judged)
    std::printf("gestures:   the right hand on %.1f %% of %lld frames (bar >= 80 %%), the right command on %.1f %%\n",
                100 * share(gesture.hand_right, gesture.judged), static_cast<long long>(gesture.judged),
                100 * share(gesture.command_right, gesture.judged));
  if (rejected) {
    std::printf("frames the hands stage refused %lld:", static_cast<long long>(rejected));
    for (const auto& [r, n] : rejections) std::printf(" %s (%lld)", r.c_str(), static_cast<long long>(n));
    std::printf("\n");
  }
  if (!o.csv_path.empty()) std::printf("per-frame CSV              %s\n", o.csv_path.c_str());
  if (!o.mp4_path.empty()) std::printf("annotated video            %s\n", o.mp4_path.c_str());
  return 0;
}

}  // namespace gpilot
