// The hands stage on a bus, used by gpilot-hands (live LCM) and gpilot-replay (a log through memq://).
// Reads CAMERA (gpilot.image_t, BGR8 or JPEG; decoded as it arrives, while the tracker works on the same
// frame) and USER_TRACK (gpilot.user_track_t), pairs them by seq, and writes HAND_OBS (gpilot.hand_obs_t) for each pair: the paper's Alg. 1 (stretched-out hand, vector
// from the shoulder centre) else Alg. 2 (hand in front of the body, vector from the body centre) else NONE.
// A frame or track that never meets its partner is dropped and counted (HEALTH rejected); a track that
// is not TRACKING gives NONE; a track made on a frame of another size is rejected.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bus_node.hpp"
#include "hands/hands_service.hpp"
#include "hands/hands_core_factory.hpp"
#include "hands/hands_channels.hpp"
#include "hands/hands_params.hpp"
#include "hands/seq_pairer.hpp"
#include "image_codec.hpp"
#include "seq_gaps.hpp"

namespace gpilot {

namespace {

// Frames' buffers kept for reuse: one waiting for its track, one being observed, one spare.
constexpr size_t kSpareBuffers = 3;

// A CAMERA frame as it waits for its track: decoded when it arrived (bgr wraps frame.data for a raw frame),
// or why it could not be, reported when the pair is made (as a frame whose track never comes is).
struct ArrivedFrame {
  image_t frame;
  cv::Mat bgr;
  std::string undecodable;
};

template <class Rect>
void copy_rect(float* out, const Rect& r) {
  out[0] = static_cast<float>(r.x);
  out[1] = static_cast<float>(r.y);
  out[2] = static_cast<float>(r.width);
  out[3] = static_cast<float>(r.height);
}

// The stage's observation of one pair: "" and the HAND_OBS, or why the method refused the frame.
std::string observe(HandMethod& method, const image_t& frame, const user_track_t& track, const cv::Mat& bgr, hand_obs_t& obs) {
  obs = hand_obs_t{};
  obs.utime = frame.utime;
  obs.seq = frame.seq;
  obs.track_id = track.track_id;
  obs.track_status = track.status;
  obs.image_width = bgr.cols;
  obs.image_height = bgr.rows;
  UserView user;
  user.box = cv::Rect2f(track.box[0], track.box[1], track.box[2], track.box[3]);
  if (track.face_box[2] > 0 && track.face_box[3] > 0)
    user.face = cv::Rect2f(track.face_box[0], track.face_box[1], track.face_box[2], track.face_box[3]);
  user.track_id = track.track_id;
  user.tracking = track.status == user_track_t::STATUS_TRACKING;
  HandsOutput r = method.observe(bgr, user, frame.utime);
  if (!r.refused.empty()) return r.refused;
  if (track.facing == user_track_t::FACING_AWAY) {
    // The paper's user faces the drone: one the tracker finds turned away gives no command, whatever the arms
    // do (BlazePose reads a back view as a front one). The pose is still read and goes out with it.
    r.kind = HandKind::None;
    r.vector = cv::Point2f(0, 0);
    r.hand_box = cv::Rect();
  }
  copy_rect(obs.user_box, r.user_box);
  obs.shoulder_centre[0] = r.shoulder_centre.x;
  obs.shoulder_centre[1] = r.shoulder_centre.y;
  obs.body_centre[0] = r.body_centre.x;
  obs.body_centre[1] = r.body_centre.y;
  obs.kind = static_cast<int8_t>(r.kind);
  obs.vector[0] = r.vector.x;
  obs.vector[1] = r.vector.y;
  copy_rect(obs.hand_box, r.hand_box);
  if (r.pose) {
    obs.method = hand_obs_t::METHOD_POSE;
    obs.pose_score = static_cast<float>(r.pose->score);
    for (int i = 0; i < kPoseLandmarkCount; ++i) {
      const PoseLandmark& l = r.pose->landmarks[i];
      obs.pose_landmarks[i][0] = l.x;
      obs.pose_landmarks[i][1] = l.y;
      obs.pose_landmarks[i][2] = l.z;
      obs.pose_landmarks[i][3] = l.visibility;
    }
  }
  if (r.skin) {
    obs.hand_skin = r.skin->detection.hand_skin;
    obs.skin_outside = r.skin->detection.skin_outside;
    obs.skin_inside = r.skin->detection.skin_inside;
    obs.skin_user_samples = r.skin->adaptation.user_samples;
    obs.skin_scene_samples = r.skin->adaptation.scene_samples;
    obs.skin_changed = static_cast<float>(r.skin->adaptation.changed_fraction);
  }
  return "";
}

}  // namespace

std::string decode_for_hands(const image_t& frame, const ImageLimits& limits, cv::Mat& bgr) {
  const std::string why = image_to_mat(frame, bgr, limits);
  if (!why.empty()) return "CAMERA seq " + std::to_string(frame.seq) + ": " + why;
  if (bgr.type() != CV_8UC3) return "CAMERA seq " + std::to_string(frame.seq) + ": skin needs colour, got GRAY8";
  return "";
}

std::string hands_on_decoded(HandMethod& method, const image_t& frame, const cv::Mat& bgr, const user_track_t& track,
                             hand_obs_t& obs) {
  if (track.image_width > 0 && (track.image_width != bgr.cols || track.image_height != bgr.rows))
    return "USER_TRACK seq " + std::to_string(track.seq) + " was made on a " + std::to_string(track.image_width) + "x" +
           std::to_string(track.image_height) + " frame, CAMERA has " + std::to_string(bgr.cols) + "x" +
           std::to_string(bgr.rows);
  const std::string refused = observe(method, frame, track, bgr, obs);
  return refused.empty() ? "" : "CAMERA seq " + std::to_string(frame.seq) + ": " + refused;
}

std::string hands_on_pair(HandMethod& method, const image_t& frame, const user_track_t& track,
                          const ImageLimits& limits, hand_obs_t& obs) {
  cv::Mat bgr;
  const std::string why = decode_for_hands(frame, limits, bgr);
  return why.empty() ? hands_on_decoded(method, frame, bgr, track, obs) : why;
}

std::shared_ptr<void> start_hands_service(const Config& config, BusNode& node) {
  return start_hands_service(config, node, make_hand_method(config.section<HandsParams>("hands")));
}

std::shared_ptr<void> start_hands_service(const Config& config, BusNode& node, std::unique_ptr<HandMethod> chosen) {
  struct State {
    State(const HandsParams& p, std::unique_ptr<HandMethod> m) : method(std::move(m)), pairer(p.match_window) {}
    std::unique_ptr<HandMethod> method;
    SeqPairer<ArrivedFrame, user_track_t> pairer;
    // Buffers of frames already observed, lent back to the bus to receive the next frame into, and to decode it
    // into: a frame costs one copy (datagram -> buffer) and its decode, no allocation, and is moved, not
    // copied, while it waits for its track.
    std::vector<std::vector<uint8_t>> spare_buffers;
    std::vector<cv::Mat> spare_pixels;
    int64_t frames_dropped = 0, tracks_dropped = 0;
    SeqGaps gaps;
    std::optional<std::pair<ArrivedFrame, user_track_t>> pending;  // the newest pair, observed when the bus is idle
  };
  const auto params = config.section<HandsParams>("hands");
  auto state = std::make_shared<State>(params, std::move(chosen));
  auto& method = *state->method;
  auto& pairer = state->pairer;
  auto& frames_dropped = state->frames_dropped;
  auto& tracks_dropped = state->tracks_dropped;
  auto& spare_buffers = state->spare_buffers;
  auto& spare_pixels = state->spare_pixels;

  const auto limits = config.section<ImageLimits>("image");
  // A pair waits in `pending` until the loop has nothing more to dispatch (BusNode::when_idle): a newer pair
  // replaces it (the older frame is skipped, counted in HEALTH.dropped), so a stage that falls behind observes
  // the newest frame, never a queue of stale ones.
  auto& pending = state->pending;
  auto recycle = [&spare_buffers, &spare_pixels](ArrivedFrame& arrived) {
    if (spare_buffers.size() < kSpareBuffers) spare_buffers.push_back(std::move(arrived.frame.data));
    if (spare_pixels.size() < kSpareBuffers && arrived.bgr.u != nullptr) spare_pixels.push_back(std::move(arrived.bgr));
  };
  auto handle = [&node, &pairer, &frames_dropped, &tracks_dropped, &pending, recycle](std::optional<std::pair<ArrivedFrame, user_track_t>> pair) {
    for (; frames_dropped < pairer.dropped_frames(); ++frames_dropped)
      node.reject("CAMERA frame without a USER_TRACK of the same seq (dropped after hands.match_window seqs)");
    for (; tracks_dropped < pairer.dropped_tracks(); ++tracks_dropped)
      node.reject("USER_TRACK without a CAMERA frame of the same seq (dropped after hands.match_window seqs)");
    if (!pair) return;
    if (pending) {
      recycle(pending->first);
      node.drop();
    }
    pending = std::move(pair);
  };
  node.when_idle("hands", [&node, &method, &pending, recycle] {
    if (!pending) return false;
    auto pair = std::move(*pending);
    pending.reset();
    auto& [arrived, track] = pair;
    hand_obs_t obs;
    const std::string why =
        arrived.undecodable.empty() ? hands_on_decoded(method, arrived.frame, arrived.bgr, track, obs) : arrived.undecodable;
    recycle(arrived);
    if (!why.empty()) {
      node.reject(why);
      return true;
    }
    publish(node, hands_channels::kHandObs, obs);
    node.set_state(health_t::STATE_OK, method.description());
    return true;
  });
  // A short CAMERA queue (hands.camera_queue) holds the frames that arrive during an observation; LCM drops
  // those that find it full. A skipped frame (a seq gap, or a pair replaced while pending) is counted in
  // HEALTH.dropped, and gpilot-replay gives a replay only the frames this stage published a HAND_OBS of.
  auto& gaps = state->gaps;
  subscribe_taking(node, hands_channels::kCamera, [&node, &gaps, handle, &pairer, &spare_buffers, &spare_pixels, limits](image_t& m, int64_t) {
    for (int64_t n = gaps.skipped_before(m.seq); n > 0; --n) node.drop();
    ArrivedFrame arrived{std::move(m), {}, {}};  // the received bytes themselves
    if (!spare_buffers.empty()) {
      m.data = std::move(spare_buffers.back());
      spare_buffers.pop_back();
    }
    if (!spare_pixels.empty()) {
      arrived.bgr = std::move(spare_pixels.back());
      spare_pixels.pop_back();
    }
    arrived.undecodable = decode_for_hands(arrived.frame, limits, arrived.bgr);
    const int64_t seq = arrived.frame.seq;
    handle(pairer.add_frame(seq, std::move(arrived)));
  }, params.camera_queue);
  subscribe(node, hands_channels::kUserTrack, [handle, &pairer](const user_track_t& m, int64_t) { handle(pairer.add_track(m.seq, m)); });
  node.set_state(health_t::STATE_DEGRADED, "waiting for CAMERA and USER_TRACK");
  return state;
}

}  // namespace gpilot
