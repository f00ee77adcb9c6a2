// The tracker stage on a bus, used by gpilot-tracker (live LCM) and gpilot-replay (a log through memq://).
// Reads CAMERA (image_t) and TRACKER_INIT (tracker_init_t); writes USER_TRACK (user_track_t, one per
// accepted frame, with that frame's seq and utime, and the face box on the frames where the cascade found it)
// and HEALTH. A frame that does not decode or that the tracker cannot use is rejected (counted in HEALTH) and
// does not advance the track.
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "bus_node.hpp"
#include "clock.hpp"
#include "face_cascade.hpp"
#include "image_codec.hpp"
#include "seq_gaps.hpp"
#include "tracker_channels.hpp"
#include "tracker_service.hpp"
#include "user_tracker.hpp"

#include "gpilot/image_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "gpilot/user_track_t.hpp"

namespace gpilot {

user_track_t to_message(const TrackOutput& t, const image_t& frame) {
  user_track_t m{};
  m.utime = frame.utime;
  m.seq = frame.seq;
  m.status = static_cast<int8_t>(t.status);
  m.box[0] = static_cast<float>(t.box.x);
  m.box[1] = static_cast<float>(t.box.y);
  m.box[2] = static_cast<float>(t.box.width);
  m.box[3] = static_cast<float>(t.box.height);
  m.confidence = static_cast<float>(t.confidence);
  if (t.face) {  // else all zero: not looked for or not found in this frame
    m.face_box[0] = static_cast<float>(t.face->x);
    m.face_box[1] = static_cast<float>(t.face->y);
    m.face_box[2] = static_cast<float>(t.face->width);
    m.face_box[3] = static_cast<float>(t.face->height);
  }
  m.init_source = static_cast<int8_t>(t.init);
  m.facing = static_cast<int8_t>(t.facing);
  m.track_id = t.track_id;
  m.image_width = frame.width;
  m.image_height = frame.height;
  return m;
}

namespace {

// What the person search cost (tracker.person): the time of the frames it ran on, and of every frame processed
// while not tracking, measured here (the core reads no clock); and how far a LOST search had to spread.
struct SearchCost {
  int64_t searching_frames = 0, searching_us = 0;
  int64_t person_frames = 0, person_us = 0;

  void add(bool searching, bool person_ran, int64_t us) {
    if (searching) ++searching_frames, searching_us += us;
    if (person_ran) ++person_frames, person_us += us;
  }
  std::string text(const gpilot::PersonSearchCounters& c, int every_frames) const {
    char b[400];
    std::snprintf(b, sizeof b,
                  "; person search: %lld runs (1 searching frame in %d), %.1f ms a run, %.1f ms a searching frame, "
                  "%lld found, %lld not the user, %lld started, %lld taken back, spread over frames: %lld regions grown, "
                  "%lld whole frame",
                  static_cast<long long>(c.runs), every_frames,
                  person_frames ? 1e-3 * static_cast<double>(person_us) / static_cast<double>(person_frames) : 0.0,
                  searching_frames ? 1e-3 * static_cast<double>(searching_us) / static_cast<double>(searching_frames) : 0.0,
                  static_cast<long long>(c.detections), static_cast<long long>(c.not_user), static_cast<long long>(c.started),
                  static_cast<long long>(c.reacquired), static_cast<long long>(c.region_steps),
                  static_cast<long long>(c.whole_frame));
    return b;
  }
};

}  // namespace

std::shared_ptr<void> start_tracker_service(const gpilot::Config& config, gpilot::BusNode& node) {
  const auto params = config.section<TrackerParams>("tracker");
  return start_tracker_service(config, node, std::make_unique<UserTracker>(params, load_tracker_models(params)));
}

std::shared_ptr<void> start_tracker_service(const gpilot::Config& config, gpilot::BusNode& node,
                                            std::unique_ptr<UserTracker> built) {
  struct State {
    explicit State(std::unique_ptr<UserTracker> t) : owned(std::move(t)), tracker(*owned) {}
    std::unique_ptr<UserTracker> owned;
    gpilot::UserTracker& tracker;
    cv::Mat frame;
    gpilot::SeqGaps gaps;
    SearchCost cost;
  };
  const auto params = config.section<gpilot::TrackerParams>("tracker");
  if (!built) throw std::invalid_argument("start_tracker_service: no tracker");
  auto state = std::make_shared<State>(std::move(built));
  auto& tracker = state->tracker;
  auto& frame = state->frame;
  auto& gaps = state->gaps;
  auto& cost = state->cost;
  const auto limits = config.section<gpilot::ImageLimits>("image");

  // At most camera_queue frames wait (LCM drops the frames that arrive while the queue is full): a stage that
  // falls behind skips frames instead of answering later and later. Each skipped frame (a seq gap) is counted
  // in HEALTH.dropped; the frames it did process are those it published a USER_TRACK of (gpilot-replay gives a
  // replay exactly those).
  subscribe(node, tracker_channels::kCamera, [&node, &tracker, &frame, &gaps, &cost, limits, person = params.person](const gpilot::image_t& msg, int64_t) {
    for (int64_t n = gaps.skipped_before(msg.seq); n > 0; --n) node.drop();
    const std::string why = gpilot::image_to_mat(msg, frame, limits);
    if (!why.empty()) {
      node.reject("CAMERA seq " + std::to_string(msg.seq) + ": " + why);
      return;
    }
    gpilot::TrackOutput out;
    const bool was_tracking = tracker.last().status == gpilot::TrackStatus::kTracking;
    const int64_t t0 = gpilot::monotonic_utime();
    try {
      out = tracker.track(frame);
    } catch (const std::invalid_argument& e) {
      node.reject("CAMERA seq " + std::to_string(msg.seq) + ": " + e.what());
      return;
    }
    cost.add(!was_tracking, tracker.person_ran(), gpilot::monotonic_utime() - t0);
    publish(node, tracker_channels::kUserTrack, to_message(out, msg));
    tracker.finish(frame);  // the face re-check, after the frame's track is out
    std::string detail = out.status == gpilot::TrackStatus::kTracking
                             ? (out.facing == gpilot::Facing::kAway ? "tracking, the user turned away (no command)" : "tracking")
                         : out.status == gpilot::TrackStatus::kLost ? "user lost: searching for a face"
                                                                    : "searching for a face";
    // Faces found but not started on (their body box failed the image check), counted by reason.
    std::string refused;
    for (int r = 1; r < gpilot::kFaceRefusals; ++r) {
      const auto why = static_cast<gpilot::FaceRefusal>(r);
      if (const int64_t n = tracker.refusals(why); n > 0)
        refused += (refused.empty() ? "" : ", ") + std::to_string(n) + " " + gpilot::refusal_text(why);
    }
    if (!refused.empty()) detail += "; faces refused: " + refused;
    if (const int64_t n = tracker.other_faces(); n > 0)
      detail += "; faces not the user's (other clothes): " + std::to_string(n);
    if (const int64_t n = tracker.off_user(); n > 0)
      detail += "; tracks dropped off the user (no face, other clothes): " + std::to_string(n);
    if (person.enabled) detail += cost.text(tracker.person_counters(), person.every_frames);
    node.set_state(out.status == gpilot::TrackStatus::kTracking ? gpilot::health_t::STATE_OK
                                                                : gpilot::health_t::STATE_DEGRADED,
                   detail);
  }, params.camera_queue);

  subscribe(node, tracker_channels::kTrackerInit, [&node, &tracker](const gpilot::tracker_init_t& msg, int64_t) {
    if (msg.command == gpilot::tracker_init_t::COMMAND_RESET) {
      tracker.reset();
      return;
    }
    const std::string why = tracker.set_box(cv::Rect2d(msg.box[0], msg.box[1], msg.box[2], msg.box[3]));
    if (!why.empty()) node.reject("TRACKER_INIT from '" + msg.source + "': " + why);
  });

  node.set_state(gpilot::health_t::STATE_DEGRADED, "no frame yet");
  return state;
}

}  // namespace gpilot
