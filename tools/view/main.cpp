// gpilot-view: watch a run, live or from its log, with the paper's red marks drawn on each frame.
// Reads CAMERA, USER_TRACK, HAND_OBS, GESTURE_CMD, GROUND_TRUTH (per frame, matched by seq: see
// frame_matcher.hpp), VEHICLE_STATE, FLIGHT_SETPOINT and HEALTH (latest, for the HUD).
// Writes (live window only): TRACKER_INIT (drag a box: manual init; 'r': reset) and FLIGHT_CONTROL
// ('e' engage, 'd' disengage, 'l' land); HEALTH once a second when live.
// Without a display (or with --headless) it writes an MP4 and/or PNGs; live headless runs until
// SIGINT/SIGTERM and then closes the MP4 cleanly.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <sys/stat.h>

#include <opencv2/highgui.hpp>
#include <opencv2/imgproc.hpp>

#include "bus_node.hpp"
#include "channels.hpp"
#include "clock.hpp"
#include "frame_matcher.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "image_codec.hpp"
#include "log.hpp"
#include "log_reader.hpp"
#include "overlay.hpp"
#include "service_cli.hpp"
#include "video_sink.hpp"

namespace gpilot {
namespace {

constexpr const char* kName = "gpilot-view";
constexpr const char* kWindow = "gpilot-view";

struct ViewOptions {
  std::string log;
  bool headless = false;
  std::string video;
  std::vector<std::string> png_every;  // N DIR
  double fps = 0;
  int hold = 0;  // 0: 12 frames live (about 0.5 s at 25 fps), 50 from a log (no hurry there)
  double speed = -1;  // log playback speed in a window; <= 0: as fast as it draws
  OverlayOptions overlay;
};

class Viewer {
 public:
  Viewer(const ViewOptions& o, bool window) : o_(o), window_(window), matcher_(o.hold) {
    int png_n = 0;
    std::string png_dir;
    if (o.png_every.size() == 2) {
      png_n = std::stoi(o.png_every[0]);
      png_dir = o.png_every[1];
    }
    if (!o.video.empty() || png_n > 0) sink_ = std::make_unique<VideoSink>(o.video, o.fps, png_dir, png_n);
    if (window_) {
      cv::namedWindow(kWindow, cv::WINDOW_AUTOSIZE | cv::WINDOW_GUI_NORMAL);  // image pixels = window pixels
      cv::setMouseCallback(kWindow, &Viewer::on_mouse, this);
    }
  }

  // Subscribes every channel the viewer reads through add(channel, handler): BusNode or LogDispatcher.
  template <class Add>
  void connect(Add&& add) {
    add(channel::kCamera, std::function<void(const image_t&, int64_t)>([this](const image_t& m, int64_t) {
          ++frames_in_;
          matcher_.add_frame(m);
        }));
    add(channel::kUserTrack, std::function<void(const user_track_t&, int64_t)>(
                                 [this](const user_track_t& m, int64_t) { matcher_.add(m); }));
    add(channel::kHandObs, std::function<void(const hand_obs_t&, int64_t)>(
                               [this](const hand_obs_t& m, int64_t) { matcher_.add(m); }));
    add(channel::kGestureCmd, std::function<void(const gesture_cmd_t&, int64_t)>(
                                  [this](const gesture_cmd_t& m, int64_t) { matcher_.add(m); }));
    add(channel::kGroundTruth, std::function<void(const ground_truth_t&, int64_t)>(
                                   [this](const ground_truth_t& m, int64_t) { matcher_.add(m); }));
    add(channel::kVehicleState, std::function<void(const vehicle_state_t&, int64_t)>(
                                    [this](const vehicle_state_t& m, int64_t) { hud_.vehicle = m; }));
    add(channel::kFlightSetpoint, std::function<void(const flight_setpoint_t&, int64_t)>(
                                      [this](const flight_setpoint_t& m, int64_t) { hud_.setpoint = m; }));
    add(channel::kHealth, std::function<void(const health_t&, int64_t)>([this](const health_t& m, int64_t) {
          if (m.name != kName) hud_.stage_hz[m.name] = m.rate_out_hz;
        }));
  }

  void set_bus(BusNode* node) { node_ = node; }

  // Draws what the matcher has released; false when the user asked to quit.
  bool draw_ready(bool flush = false) {
    for (auto& f : flush ? matcher_.flush() : matcher_.take_ready())
      if (!draw(f)) return false;
    return !quit_;
  }

  // Keeps the window alive between frames; false when the user asked to quit or closed it.
  bool poll_window(int wait_ms) {
    if (!window_) return !quit_;
    handle_key(cv::waitKey(std::max(1, wait_ms)));
    if (cv::getWindowProperty(kWindow, cv::WND_PROP_VISIBLE) < 1) quit_ = true;
    return !quit_;
  }

  std::string status() const {
    return "received " + std::to_string(frames_in_) + " frames, drew " + std::to_string(drawn_) + " (" +
           std::to_string(matcher_.incomplete_frames()) + " with messages missing), " +
           std::to_string(matcher_.late_messages()) + " late messages, " + std::to_string(bad_images_) +
           " bad images";
  }

  void finish() {
    if (sink_) sink_->close();
    if (window_) cv::destroyAllWindows();
  }

  const VideoSink* sink() const { return sink_.get(); }
  int64_t bad_images() const { return bad_images_; }

 private:
  bool draw(const MatchedFrame& f) {
    cv::Mat frame;
    const std::string why = image_to_mat(f.image, frame);
    if (!why.empty()) {
      ++bad_images_;
      if (node_) node_->reject("CAMERA seq " + std::to_string(f.image.seq) + ": " + why);
      return true;
    }
    const cv::Mat annotated = draw_overlay(frame, f.image.seq, f.msgs, hud_, o_.overlay);
    ++drawn_;
    if (sink_) sink_->write(annotated, f.image.seq, f.image.utime);
    if (!window_) return true;
    frame_size_ = frame.size();
    shown_ = annotated;
    cv::imshow(kWindow, shown_);
    return pace(f.image.utime);
  }

  // Log playback in a window follows the frames' utimes at --speed; live frames are shown as they come.
  bool pace(int64_t utime) {
    int wait_ms = 1;
    if (node_ == nullptr && o_.speed > 0) {
      if (first_utime_ < 0) {
        first_utime_ = utime;
        wall_start_ = monotonic_utime();
      }
      const int64_t due = wall_start_ + static_cast<int64_t>((utime - first_utime_) / o_.speed);
      wait_ms = static_cast<int>(std::max<int64_t>(1, (due - monotonic_utime()) / 1000));
    }
    return poll_window(wait_ms);
  }

  void handle_key(int key) {
    if (key < 0) return;
    key &= 0xff;
    if (key == 'q' || key == 27) quit_ = true;
    if (key == 'r') send_tracker_init(tracker_init_t::COMMAND_RESET, cv::Rect());
    if (key == 'e') send_flight_control(flight_control_t::COMMAND_ENGAGE);
    if (key == 'd') send_flight_control(flight_control_t::COMMAND_DISENGAGE);
    if (key == 'l') send_flight_control(flight_control_t::COMMAND_LAND);
  }

  static void on_mouse(int event, int x, int y, int, void* self) {
    auto& v = *static_cast<Viewer*>(self);
    if (event == cv::EVENT_LBUTTONDOWN) v.drag_.press(x, y);
    if (event == cv::EVENT_MOUSEMOVE && v.drag_.active()) {
      v.drag_.move(x, y);
      if (!v.shown_.empty()) {
        cv::Mat rubber = v.shown_.clone();
        cv::rectangle(rubber, v.drag_.current(), cv::Scalar(255, 255, 0), 1);
        cv::imshow(kWindow, rubber);
      }
    }
    if (event == cv::EVENT_LBUTTONUP)
      if (const auto box = v.drag_.release(x, y, v.frame_size_)) v.send_tracker_init(tracker_init_t::COMMAND_SET_BOX, *box);
  }

  void send_tracker_init(int8_t command, const cv::Rect& box) {
    if (!node_) {
      log_warn("no bus in --log mode: TRACKER_INIT not sent");
      return;
    }
    tracker_init_t m{};
    m.utime = wall_utime();
    m.seq = ++init_seq_;
    m.command = command;
    m.box[0] = static_cast<float>(box.x);
    m.box[1] = static_cast<float>(box.y);
    m.box[2] = static_cast<float>(box.width);
    m.box[3] = static_cast<float>(box.height);
    m.source = kName;
    node_->publish(channel::kTrackerInit, m);
    log_info("TRACKER_INIT %s %d,%d %dx%d", command == tracker_init_t::COMMAND_RESET ? "reset" : "box", box.x, box.y,
             box.width, box.height);
  }

  void send_flight_control(int8_t command) {
    if (!node_) {
      log_warn("no bus in --log mode: FLIGHT_CONTROL not sent");
      return;
    }
    flight_control_t m{};
    m.utime = wall_utime();
    m.seq = ++control_seq_;
    m.command = command;
    m.source = kName;
    node_->publish(channel::kFlightControl, m);
    log_info("FLIGHT_CONTROL %d", command);
  }

  const ViewOptions& o_;
  bool window_;
  FrameMatcher matcher_;
  HudState hud_;
  std::unique_ptr<VideoSink> sink_;
  BusNode* node_ = nullptr;
  BoxDrag drag_;
  cv::Mat shown_;
  cv::Size frame_size_;
  int64_t frames_in_ = 0, drawn_ = 0, bad_images_ = 0;
  int64_t init_seq_ = 0, control_seq_ = 0;
  int64_t first_utime_ = -1, wall_start_ = 0;
  bool quit_ = false;
};

void report(const Viewer& v) {
  log_info("%s", v.status().c_str());
  if (const VideoSink* s = v.sink()) {
    if (s->frames_written() == 0 && s->pngs_written() == 0)
      log_warn("no frame was drawn: nothing written");
    if (s->frames_written() > 0)
      log_info("MP4: %lld frames at %.2f fps (%s)", static_cast<long long>(s->frames_written()), s->fps(),
               s->fourcc().c_str());
    if (s->pngs_written() > 0)
      log_info("%lld PNG files", static_cast<long long>(s->pngs_written()));
  }
}

// The CAMERA rate over the whole log (a first pass; utimes only), so a video plays at the run's pace even
// when its first frames came slowly.
double log_camera_rate(const std::string& path) {
  LogReader log(path);
  LogDispatcher d;
  std::vector<int64_t> utimes;
  d.on<image_t>(channel::kCamera, [&](const image_t& m, int64_t) { utimes.push_back(m.utime); });
  LogEvent ev;
  while (log.next(ev)) d.dispatch(ev);
  std::sort(utimes.begin(), utimes.end());
  return rate_from_utimes(utimes, 0.0);
}

int run_log(ViewOptions o, bool window) {
  if (!o.video.empty() && o.fps <= 0) o.fps = log_camera_rate(o.log);
  LogReader log(o.log);
  LogDispatcher dispatch;
  Viewer viewer(o, window);
  viewer.connect([&](const char* ch, auto handler) { dispatch.on(ch, handler); });
  Progress progress(kName);
  LogEvent ev;
  bool go_on = true;
  while (go_on && log.next(ev)) {
    dispatch.dispatch(ev);
    go_on = viewer.draw_ready();
    progress.update(log, viewer.status());
  }
  if (go_on) viewer.draw_ready(true);
  for (const auto& w : log.warnings()) log_warn("%s", w.c_str());
  if (dispatch.rejected_total() > 0)
    log_warn("%lld messages did not decode or were invalid (last: %s)", static_cast<long long>(dispatch.rejected_total()),
             dispatch.last_reject_reason().c_str());
  while (window && go_on && viewer.poll_window(50)) {
  }
  viewer.finish();
  report(viewer);
  return 0;
}

int run_live(const ViewOptions& o, bool window, const std::string& url, const BusParams& bus) {
  BusNode node(kName, url, bus);
  Viewer viewer(o, window);
  viewer.set_bus(&node);
  viewer.connect([&](const char* ch, auto handler) { node.subscribe(ch, handler); });
  node.set_state(health_t::STATE_OK, viewer.status());
  node.publish_health();
  node.every(1.0, [&] {
    node.set_state(health_t::STATE_OK, viewer.status());
    node.publish_health();
  });
  while (node.spin_once(window ? 10 : 50)) {
    if (!viewer.draw_ready() || !viewer.poll_window(1)) break;
  }
  viewer.draw_ready(true);
  viewer.finish();
  node.set_state(health_t::STATE_STOPPING, viewer.status());
  node.publish_health();
  report(viewer);
  return 0;
}

}  // namespace
}  // namespace gpilot

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli(kName,
                 "Shows a run with the paper's marks in red: user box, hand square, the command from the shoulder "
                 "centre (arrow: FINE/UP/DOWN, cross: CLOSER, circle: FURTHER), and a HUD (mode, buffers, track, "
                 "vehicle, per-stage rates). Live from LCM (default) or from a log (--log). In the window: drag a "
                 "box to initialise the tracker (TRACKER_INIT), 'r' reset the tracker, 'e'/'d'/'l' engage/"
                 "disengage/land (FLIGHT_CONTROL), 'q' quit. Without a display it writes --video and/or "
                 "--png-every; live headless runs until SIGINT/SIGTERM.");
  ViewOptions o;
  auto& app = cli.app();
  app.add_option("--log", o.log, "read this LCM log instead of the live bus");
  app.add_flag("--headless", o.headless, "no window, even when a display is there");
  app.add_option("--video", o.video, "write the annotated frames to this MP4");
  app.add_option("--png-every", o.png_every, "write every N-th annotated frame as DIR/frame_<seq>.png")
      ->expected(2)
      ->type_name("N DIR");
  app.add_option("--fps", o.fps, "MP4 frame rate (default: from the frames' utimes)")->check(CLI::Range(0.0, 240.0));
  app.add_option("--hold", o.hold, "newer frames to wait for a frame's messages before drawing it anyway (default 12 live, 50 from a log)")
      ->check(CLI::Range(0, 1000));
  app.add_option("--speed", o.speed, "log playback speed in a window (default 1; 0: as fast as it draws)");
  app.add_flag("--truth", o.overlay.truth, "draw GROUND_TRUTH in green (true box, hands, expected mode)");
  app.add_flag("--skin-overlay", o.overlay.skin, "show the skin counts of HAND_OBS (and a skin mask when available)");
  app.add_flag("!--no-hud", o.overlay.hud, "no HUD strip under the frames");
  return cli.run(argc, argv, [&](const Config& config) {
    if (o.png_every.size() == 2) {
      int n = 0;
      try {
        n = std::stoi(o.png_every[0]);
      } catch (const std::exception&) {
      }
      if (n <= 0) throw std::invalid_argument("--png-every needs a positive N, got '" + o.png_every[0] + "'");
      struct stat st {};
      if (::stat(o.png_every[1].c_str(), &st) != 0 && ::mkdir(o.png_every[1].c_str(), 0755) != 0)
        throw std::runtime_error("cannot create " + o.png_every[1]);
    }
    const char* display = std::getenv("DISPLAY");
    const bool window = !o.headless && display && *display;
    if (!window && !o.headless) log_warn("no display: running headless");
    if (!window && o.video.empty() && o.png_every.empty())
      throw std::invalid_argument("nothing to do without a window: give --video OUT.mp4 and/or --png-every N DIR");
    if (o.speed < 0) o.speed = window ? 1.0 : 0.0;
    if (o.hold <= 0) o.hold = o.log.empty() ? 12 : 50;
    if (!o.log.empty()) return run_log(o, window);
    return run_live(o, window, resolve_lcm_url(cli.lcm_url()), config.section<BusParams>("bus"));
  });
}
