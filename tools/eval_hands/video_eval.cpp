#include "video_eval.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "paths.hpp"
#include "capture/frame_sources.hpp"
#include "decide/decide_service.hpp"
#include "hands/hands_params.hpp"
#include "hands/hands_service.hpp"
#include "image_codec.hpp"
#include "image_codec_params.hpp"
#include "overlay.hpp"
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

const char* kind_name(int8_t k) {
  return k == hand_obs_t::KIND_OUT ? "OUT" : k == hand_obs_t::KIND_FRONT ? "FRONT" : "NONE";
}

}  // namespace

int run_video_eval(const VideoEvalOptions& o, const Config& config) {
  if (o.gesture != "none") throw std::runtime_error("--gesture '" + o.gesture + "': only 'none' is known");
  auto source = open_source(o);
  const double fps = source->fps() > 0 ? source->fps() : o.fps;
  const auto tracker_params = config.section<TrackerParams>("tracker");
  UserTracker tracker(tracker_params);
  if (!o.init_box.empty()) {
    const std::string why = tracker.set_box(parse_init_box(o.init_box));
    if (!why.empty()) throw std::runtime_error("--init-box: " + why);
  }
  const auto hands = config.section<HandsParams>("hands");
  HandObserver observer(hands, SkinModel::load(resolve_project_path(hands.skin.model)), tracker_params.body());
  GestureDecider decider(config.section<DecideParams>("decide"));
  const auto limits = config.section<ImageLimits>("image");

  std::ofstream csv;
  if (!o.csv_path.empty()) {
    csv.open(o.csv_path);
    if (!csv) throw std::runtime_error("cannot write " + o.csv_path);
    csv << "frame,track_status,box_x,box_y,box_w,box_h,face,hand_kind,vector_x,vector_y,hand_skin,skin_outside,skin_inside,"
           "mode,n_out,n_front_higher,n_front_lower,rejected\n";
  }
  std::unique_ptr<VideoSink> sink;
  if (!o.mp4_path.empty()) sink = std::make_unique<VideoSink>(o.mp4_path, fps, "", 0);
  OverlayOptions overlay;
  overlay.skin = true;

  int64_t frames = 0, tracking = 0, decided = 0, moving = 0, rejected = 0, faces = 0, tracks_started = 0;
  std::map<std::string, int64_t> kinds, modes, rejections;
  int32_t last_track = 0;
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
    const std::string reason = hands_on_pair(observer, image, track, limits, obs);
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
    if (csv) {
      csv << seq << ',' << track_status_name(track.status);
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

  const int64_t hands_seen = kinds["OUT"] + kinds["FRONT"];
  const double moving_share = decided ? static_cast<double>(moving) / static_cast<double>(decided) : 0.0;
  const double hand_share = tracking ? static_cast<double>(hands_seen) / static_cast<double>(tracking) : 0.0;
  if (o.json) {
    nlohmann::json j = {{"mode", "video"},
                        {"source", o.source},
                        {"gesture", o.gesture},
                        {"init", o.init_box.empty() ? "face search" : "box " + o.init_box},
                        {"fps", fps},
                        {"frames", frames},
                        {"frames_tracking", tracking},
                        {"tracks_started", tracks_started},
                        {"faces_handed_over", faces},
                        {"hand_kinds_tracking", kinds},
                        {"false_hand_share", hand_share},
                        {"frames_decided", decided},
                        {"modes", modes},
                        {"moving_command_frames", moving},
                        {"moving_command_share", moving_share},
                        {"frames_rejected", rejected},
                        {"rejections", rejections}};
    std::cout << j.dump() << std::endl;
    return 0;
  }
  std::printf("%s: %lld frames at %.1f fps, the person makes %s gesture; user from %s\n\n", o.source.c_str(),
              static_cast<long long>(frames), fps, o.gesture == "none" ? "no" : o.gesture.c_str(),
              o.init_box.empty() ? "the tracker's face search" : ("box " + o.init_box).c_str());
  std::printf("frames TRACKING            %lld of %lld (%lld tracks started, a face handed over on %lld frames)\n",
              static_cast<long long>(tracking), static_cast<long long>(frames), static_cast<long long>(tracks_started),
              static_cast<long long>(faces));
  std::printf("hand kinds while TRACKING  NONE %lld  OUT %lld  FRONT %lld: a hand (false) on %.1f %%\n",
              static_cast<long long>(kinds["NONE"]), static_cast<long long>(kinds["OUT"]),
              static_cast<long long>(kinds["FRONT"]), 100.0 * hand_share);
  std::printf("commands                  ");
  for (const auto& [m, n] : modes) std::printf(" %s %lld", m.c_str(), static_cast<long long>(n));
  std::printf("\nmoving command (false)     %lld of %lld decided frames (%.1f %%)\n", static_cast<long long>(moving),
              static_cast<long long>(decided), 100.0 * moving_share);
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
