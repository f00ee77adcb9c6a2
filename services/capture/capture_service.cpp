// The capture loop (see capture_service.hpp): one source, real-time pacing on the monotonic clock while the
// bus is served between frames, and clear HEALTH states for a source that ends, is lost or cannot open.
#include "capture_service.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>

#include "capture_channels.hpp"
#include "capture_params.hpp"
#include "clock.hpp"
#include "frame_sources.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/vehicle_state_t.hpp"
#include "image_codec.hpp"
#include "log.hpp"
#include "synthetic_world.hpp"

namespace gpilot {
namespace {

// A paced source this many frame periods behind its ticks (a stall: a slow disk, a stopped process) restarts
// its ticks from now instead of publishing the missed frames in a burst to catch up.
constexpr int64_t kStallPeriods = 10;

ground_truth_t to_message(const SyntheticTruth& t, int64_t utime, int64_t seq) {
  ground_truth_t m{};
  m.utime = utime;
  m.seq = seq;
  const auto box = [](const cv::Rect2f& r, float* out) { out[0] = r.x, out[1] = r.y, out[2] = r.width, out[3] = r.height; };
  const auto pt = [](const cv::Point2f& p, float* out) { out[0] = p.x, out[1] = p.y; };
  box(t.user_box, m.user_box);
  box(t.face_box, m.face_box);
  pt(t.shoulder_centre, m.shoulder_centre);
  pt(t.body_centre, m.body_centre);
  pt(t.left_hand, m.left_hand);
  pt(t.right_hand, m.right_hand);
  m.hand_size = t.hand_size;
  m.gesture = static_cast<int8_t>(t.gesture);
  m.expected_kind = static_cast<int8_t>(t.expected_kind);
  pt(t.expected_vector, m.expected_vector);
  m.expected_mode = static_cast<int8_t>(t.expected_mode);
  m.expected_direction[0] = t.expected_direction.x;
  m.expected_direction[1] = t.expected_direction.y;
  m.expected_direction[2] = t.expected_direction.z;
  m.person_position[0] = t.person_position.x;
  m.person_position[1] = t.person_position.y;
  m.person_position[2] = t.person_position.z;
  m.camera_position[0] = static_cast<float>(t.camera.north);
  m.camera_position[1] = static_cast<float>(t.camera.east);
  m.camera_position[2] = static_cast<float>(t.camera.down);
  m.camera_yaw = static_cast<float>(t.camera.yaw);
  return m;
}

// One frame from whichever source: the frame, its utime and (synthetic world) its ground truth.
struct Produced {
  cv::Mat bgr;        // or, with `jpeg`, the source's own JPEG bytes in one row
  bool jpeg = false;
  int64_t utime = 0;
  std::optional<SyntheticTruth> truth;
};

// The opened source: the one object of its kind, and a producer of frame `seq` (stamped on the node's clock).
struct OpenSource {
  std::unique_ptr<SyntheticWorld> world;
  std::unique_ptr<FrameSource> file;
  std::unique_ptr<CameraSource> camera;
  std::function<ReadStatus(int64_t, Produced&, std::string&)> produce;
  double fps = 0.0;
  std::string opened;  // what was opened, for the log and HEALTH
};

// Opens the source o names; throws when it cannot (a camera that is not there yet is not an error: the loop
// reports it lost and retries). The synthetic camera flies with `vehicle`, the latest VEHICLE_STATE.
OpenSource open_source(const CaptureParams& p, int8_t format, const CaptureOptions& o, BusNode& node,
                       const std::optional<CameraPose>& vehicle) {
  OpenSource src;
  switch (o.kind) {
    case CaptureOptions::Kind::Synthetic: {
      src.world = std::make_unique<SyntheticWorld>(p.synthetic, Scenario::load(o.source), o.seed);
      const SyntheticWorld* world = src.world.get();
      const double fps = src.fps = p.synthetic.fps;
      char what[512];
      std::snprintf(what, sizeof what, "synthetic scenario '%s' (%s, %g s @ %g fps)", world->scenario().name().c_str(),
                    world->scenario().origin().c_str(), world->scenario().duration_s(), fps);
      src.opened = what;
      src.produce = [world, fps, &vehicle, &node](int64_t seq, Produced& out, std::string& why) {
        const double t = static_cast<double>(seq) / fps;  // scenario time of this frame
        if (t >= world->scenario().duration_s()) {
          why = "end of scenario '" + world->scenario().name() + "' after " + std::to_string(seq) + " frames";
          return ReadStatus::End;
        }
        SyntheticFrame f = world->render(t, seq, vehicle);
        out.utime = node.now();
        out.bgr = std::move(f.bgr);
        out.truth = f.truth;
        return ReadStatus::Frame;
      };
      break;
    }
    case CaptureOptions::Kind::Video:
    case CaptureOptions::Kind::Images: {
      if (o.kind == CaptureOptions::Kind::Video)
        src.file = std::make_unique<VideoFileSource>(o.source, o.loop,
                                                     format == image_t::PIXEL_FORMAT_JPEG && p.jpeg_passthrough);
      else
        src.file = std::make_unique<ImageFolderSource>(o.source, p.fps, o.loop);
      FrameSource* file = src.file.get();
      src.fps = file->fps();
      src.opened = file->describe();
      src.produce = [file, &node](int64_t, Produced& out, std::string& why) {
        const ReadStatus s = file->read(out.bgr, why);
        out.jpeg = file->gives_jpeg();
        // Stamped when read, on the bus clock like a camera's: the file's own time (media_time_s) is not a
        // time on the bus, and downstream stages judge freshness and latency by utime.
        out.utime = node.now();
        return s;
      };
      break;
    }
    case CaptureOptions::Kind::Camera: {
      src.camera = std::make_unique<CameraSource>(o.camera_index, p.width, p.height, p.fps);
      CameraSource* camera = src.camera.get();
      std::string why;
      src.opened = camera->open(why) ? camera->describe() : why;
      src.fps = camera->fps();
      src.produce = [camera, &node](int64_t, Produced& out, std::string& why) {
        const ReadStatus s = camera->read(out.bgr, why);
        out.utime = node.now();
        return s;
      };
      break;
    }
  }
  return src;
}

// Publishes frame f as CAMERA seq (and its GROUND_TRUTH); false (counted in HEALTH, nothing published) when
// the source's own JPEG is not one the stages could decode.
bool publish_frame(BusNode& node, const Produced& f, int64_t seq, int8_t format, const CaptureParams& p,
                   JpegChroma chroma) {
  image_t img;
  if (f.jpeg) {
    const std::string bad = jpeg_to_image(f.bgr.data, f.bgr.total(), f.utime, seq, img);
    if (!bad.empty()) {  // a damaged frame of the file: counted, not published
      log_warn("frame %lld of the source is not a JPEG the stages could decode: %s", static_cast<long long>(seq), bad.c_str());
      node.reject(bad);
      return false;
    }
  } else {
    img = mat_to_image(f.bgr, f.utime, seq, format, p.jpeg_quality, chroma);
  }
  publish(node, capture_channels::kCamera, img);
  if (f.truth) publish(node, capture_channels::kGroundTruth, to_message(*f.truth, f.utime, seq));
  return true;
}

}  // namespace

int run_capture(const Config& config, const CaptureOptions& o, BusNode& node) {
  const CaptureParams p = config.section<CaptureParams>("capture");
  const int8_t format = pixel_format_from_name(p.pixel_format);
  if (format < 0) throw ConfigError("capture.pixel_format: '" + p.pixel_format + "' is not BGR8, GRAY8 or JPEG");
  JpegChroma chroma = JpegChroma::k420;
  if (!jpeg_chroma_from_name(p.jpeg_chroma, chroma))
    throw ConfigError("capture.jpeg_chroma: '" + p.jpeg_chroma + "' is not 444, 422 or 420");

  std::optional<CameraPose> vehicle;  // the latest VEHICLE_STATE: the synthetic camera flies with it
  subscribe(node, capture_channels::kVehicleState, [&vehicle](const vehicle_state_t& m, int64_t) {
    vehicle = CameraPose{m.position[0], m.position[1], m.position[2], m.attitude[2]};
  });
  node.every(1.0, [&node] { node.publish_health(); });

  OpenSource src;
  try {
    src = open_source(p, format, o, node, vehicle);
  } catch (const std::exception& e) {
    // A source that cannot open: said on stderr and in HEALTH, exit status 1.
    log_error("%s", e.what());
    node.set_state(health_t::STATE_ERROR, e.what());
    node.publish_health();
    return 1;
  }
  const CameraSource* camera = src.camera.get();
  std::string& opened = src.opened;
  if (!camera || camera->is_open())
    log_info("publishing CAMERA%s from %s", src.world ? " and GROUND_TRUTH" : "", opened.c_str());
  node.set_state(health_t::STATE_OK, opened);
  node.publish_health();

  const double fps = src.fps;
  const int64_t max_frames = o.duration_s > 0 ? static_cast<int64_t>(std::ceil(o.duration_s * fps - 1e-9)) : -1;
  const int64_t period = std::max<int64_t>(1, seconds_to_utime(1.0 / fps));
  int64_t next_tick = monotonic_utime();
  int64_t seq = 0, last_utime = 0;
  bool degraded = false;
  auto finish = [&](const std::string& why) {
    log_info("%s", why.c_str());
    node.set_state(health_t::STATE_STOPPING, why);
    node.publish_health();
    return 0;
  };
  // Serves the bus (VEHICLE_STATE, timers) until the monotonic clock reaches `until`; what is queued is served
  // even when `until` has passed (a frame rendered late on a loaded machine): without it the camera stood still
  // for 3.8 s while the drone flew, then jumped 1.5 m.
  auto serve_until = [&](int64_t until) {
    node.drain();
    node.spin_once(0);
    for (int64_t now = monotonic_utime(); now < until && !node.stopping(); now = monotonic_utime())
      node.spin_once(static_cast<int>(std::max<int64_t>(0, (until - now) / 1000)));
  };

  while (!node.stopping()) {
    if (max_frames >= 0 && seq >= max_frames) return finish("--duration reached after " + std::to_string(seq) + " frames");
    Produced f;
    std::string why;
    switch (src.produce(seq, f, why)) {
      case ReadStatus::Frame: {
        f.utime = std::max(f.utime, last_utime + 1);  // each frame its own time, even read within a microsecond
        last_utime = f.utime;
        if (!publish_frame(node, f, seq, format, p, chroma)) break;
        ++seq;
        if (degraded) {
          degraded = false;
          opened = camera ? camera->describe() : opened;
          log_info("source back: %s", opened.c_str());
          node.set_state(health_t::STATE_OK, opened);
        }
        break;
      }
      case ReadStatus::Skip:
        log_warn("%s", why.c_str());
        node.reject(why);
        break;
      case ReadStatus::End:
        return finish(why);
      case ReadStatus::Lost: {
        char every[64];
        std::snprintf(every, sizeof every, "; retrying every %g s", p.camera_retry_s);
        const std::string detail = why + every;
        if (!degraded) log_warn("%s", detail.c_str());
        degraded = true;
        node.set_state(health_t::STATE_DEGRADED, detail);
        serve_until(monotonic_utime() + seconds_to_utime(p.camera_retry_s));
        std::string reopen_why;
        if (src.camera && src.camera->open(reopen_why)) log_info("camera reopened: %s", src.camera->describe().c_str());
        next_tick = monotonic_utime();
        continue;
      }
    }
    if (camera || o.as_fast_as_possible) {
      // No pacing here (a camera paces itself: read() blocks until its next frame): serve what is queued.
      node.drain();
      node.spin_once(0);
    } else {
      next_tick += period;
      const int64_t now = monotonic_utime();
      if (now - next_tick > kStallPeriods * period) next_tick = now;  // far behind (a stall): no burst to catch up
      serve_until(next_tick);
    }
  }
  return finish("stopped by signal after " + std::to_string(seq) + " frames");
}

}  // namespace gpilot
