#include "synthetic_run.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgproc.hpp>

#include "gpilot/flight_setpoint_t.hpp"
#include "image_codec.hpp"

namespace gpilot::test {

int8_t SyntheticRun::default_decided(int64_t s) {
  if (s <= 30) return gesture_cmd_t::MODE_HOVER;
  if (s == 40) return gesture_cmd_t::MODE_UP;
  if (s < 81) return gesture_cmd_t::MODE_FINE;
  if (s == 90) return gesture_cmd_t::MODE_FURTHER;
  return gesture_cmd_t::MODE_CLOSER;
}

cv::Rect2f user_box_of(int64_t seq) { return {60.0f + 4.0f * static_cast<float>(seq % 20), 40.0f, 80.0f, 160.0f}; }
cv::Point2f shoulder_centre_of(int64_t seq) {
  const auto b = user_box_of(seq);
  return {b.x + b.width / 2, b.y + 0.2f * b.height};
}
cv::Point2f body_centre_of(int64_t seq) {
  const auto b = user_box_of(seq);
  return {b.x + b.width / 2, b.y + b.height / 2};
}
cv::Rect2f hand_box_of(int64_t seq) {
  const auto b = user_box_of(seq);
  return {b.x + b.width + 20.0f, 60.0f, 20.0f, 20.0f};
}

cv::Mat frame_of(int64_t seq, const cv::Size& size) {
  cv::Mat f(size, CV_8UC3, cv::Scalar(128, 128, 128));
  const auto b = user_box_of(seq);
  cv::rectangle(f, cv::Rect(cv::Point(static_cast<int>(b.x) + 10, static_cast<int>(b.y) + 10),
                            cv::Point(static_cast<int>(b.x + b.width) - 10, static_cast<int>(b.y + b.height) - 10)),
                cv::Scalar(200, 120, 60), cv::FILLED);
  cv::putText(f, std::to_string(seq), cv::Point(10, size.height - 10), cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(255, 255, 255), 1);
  return f;
}

image_t camera_of(const SyntheticRun& run, int64_t seq) {
  return mat_to_image(frame_of(seq, run.size), run.t0 + seq * run.frame_period_us, seq, run.pixel_format);
}

user_track_t track_of(const SyntheticRun& run, int64_t seq) {
  user_track_t t{};
  t.utime = run.t0 + seq * run.frame_period_us;
  t.seq = seq;
  t.status = user_track_t::STATUS_TRACKING;
  const auto b = user_box_of(seq);
  t.box[0] = b.x;
  t.box[1] = b.y;
  t.box[2] = b.width;
  t.box[3] = b.height;
  t.confidence = 9.5f;
  t.init_source = user_track_t::INIT_FACE;
  t.facing = run.facing(seq);
  t.track_id = 1;
  t.image_width = run.size.width;
  t.image_height = run.size.height;
  return t;
}

hand_obs_t hand_of(const SyntheticRun& run, int64_t seq) {
  hand_obs_t h{};
  h.utime = run.t0 + seq * run.frame_period_us;
  h.seq = seq;
  h.track_id = 1;
  h.track_status = user_track_t::STATUS_TRACKING;
  const auto b = user_box_of(seq);
  h.user_box[0] = b.x;
  h.user_box[1] = b.y;
  h.user_box[2] = b.width;
  h.user_box[3] = b.height;
  const auto uc = shoulder_centre_of(seq), bc = body_centre_of(seq);
  h.shoulder_centre[0] = uc.x;
  h.shoulder_centre[1] = uc.y;
  h.body_centre[0] = bc.x;
  h.body_centre[1] = bc.y;
  h.kind = hand_obs_t::KIND_OUT;
  const auto hb = hand_box_of(seq);
  h.vector[0] = hb.x + hb.width / 2 - uc.x;
  h.vector[1] = hb.y + hb.height / 2 - uc.y;
  h.hand_box[0] = hb.x;
  h.hand_box[1] = hb.y;
  h.hand_box[2] = hb.width;
  h.hand_box[3] = hb.height;
  h.hand_skin = 300;
  h.skin_outside = 400;
  h.skin_inside = 50;
  h.image_width = run.size.width;
  h.image_height = run.size.height;
  return h;
}

gesture_cmd_t cmd_of(const SyntheticRun& run, int64_t seq) {
  gesture_cmd_t c{};
  c.utime = run.t0 + seq * run.frame_period_us;
  c.seq = seq;
  c.track_id = 1;
  c.mode = run.decided_mode(seq);
  switch (c.mode) {
    case gesture_cmd_t::MODE_FINE:
      c.direction[0] = kFineDirection[0];
      c.direction[1] = kFineDirection[1];
      break;
    case gesture_cmd_t::MODE_UP: c.direction[1] = -0.5f; break;
    case gesture_cmd_t::MODE_DOWN: c.direction[1] = 0.5f; break;
    case gesture_cmd_t::MODE_CLOSER: c.direction[2] = 1.0f; break;
    case gesture_cmd_t::MODE_FURTHER: c.direction[2] = -1.0f; break;
    default: break;
  }
  c.user_box_width = user_box_of(seq).width;
  c.n_out = 40;
  c.buffer_fill = static_cast<int16_t>(std::min<int64_t>(60, seq + 1));
  return c;
}

ground_truth_t truth_of(const SyntheticRun& run, int64_t seq) {
  ground_truth_t g{};
  g.utime = run.t0 + seq * run.frame_period_us;
  g.seq = seq;
  const auto b = user_box_of(seq);
  g.user_box[0] = b.x;
  g.user_box[1] = b.y;
  g.user_box[2] = b.width;
  g.user_box[3] = b.height;
  g.expected_mode = run.expected_mode(seq);
  g.person_position[0] = 10.0f;
  g.person_position[1] = 2.0f;
  g.person_position[2] = 0.0f;
  return g;
}

vehicle_state_t vehicle_of(const SyntheticRun& run, int64_t seq) {
  vehicle_state_t v{};
  v.utime = run.t0 + seq * run.frame_period_us + 10000;
  v.seq = seq;
  v.position[0] = 0.1f * static_cast<float>(seq);
  v.position[1] = 0.05f * static_cast<float>(seq);
  v.position[2] = -2.0f - 0.01f * static_cast<float>(seq);
  v.attitude[2] = 0.01f * static_cast<float>(seq);
  v.armed = true;
  v.source = vehicle_state_t::SOURCE_SIMULATOR;
  v.landed_state = vehicle_state_t::LANDED_IN_AIR;
  return v;
}

health_t health_of(const std::string& name, int64_t i, int64_t utime) {
  health_t h{};
  h.utime = utime;
  h.seq = i;
  h.name = name;
  h.pid = 1234;
  h.state = health_t::STATE_OK;
  h.messages_in = 25 * i;
  h.messages_out = 25 * i;
  h.rate_in_hz = h.rate_out_hz = i == 0 ? 0.0f : 24.0f + static_cast<float>((i - 1) % 3);
  h.processing_ms_p50 = 2.0f + static_cast<float>(i);
  h.processing_ms_p99 = 10.0f + static_cast<float>(i);
  h.cpu_s = 0.5 + 0.06 * static_cast<double>(i);  // 60 ms of CPU each report period (25 frames)
  return h;
}

namespace {

struct Event {
  int64_t timestamp;
  int order;  // keeps the writing order of events with the same timestamp
  std::string channel;
  std::vector<uint8_t> bytes;
};

template <class Msg>
void add(std::vector<Event>& events, int64_t ts, const std::string& channel, const Msg& m) {
  Event e{ts, static_cast<int>(events.size()), channel, {}};
  e.bytes.resize(static_cast<size_t>(m.getEncodedSize()));
  m.encode(e.bytes.data(), 0, static_cast<int>(e.bytes.size()));
  events.push_back(std::move(e));
}

}  // namespace

int64_t write_synthetic_log(const std::string& path, const SyntheticRun& run) {
  std::vector<Event> events;
  for (int64_t s = 0; s < run.frames; ++s) {
    const int64_t t = run.t0 + s * run.frame_period_us;
    add(events, t + 1000, "CAMERA", camera_of(run, s));
    if (run.with_truth) add(events, t + 1500, "GROUND_TRUTH", truth_of(run, s));
    add(events, t + 15000, "USER_TRACK", track_of(run, s));
    if (run.with_hand) add(events, t + 30000, "HAND_OBS", hand_of(run, s));
    const int64_t cmd_at = t + run.cmd_latency_us(s);
    add(events, cmd_at, "GESTURE_CMD", cmd_of(run, s));
    flight_setpoint_t sp{};
    sp.utime = cmd_at + 5000;
    sp.seq = s;
    sp.engaged = true;
    sp.mode = run.decided_mode(s);
    add(events, cmd_at + 5000, "FLIGHT_SETPOINT", sp);
    add(events, t + 10000, "VEHICLE_STATE", vehicle_of(run, s));
    if (run.with_health && s % 25 == 24) {
      add(events, t + 20000, "HEALTH", health_of("gpilot-tracker", s / 25, t + 20000));
      add(events, t + 20001, "HEALTH", health_of("gpilot-decide", s / 25, t + 20001));
    }
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return std::tie(a.timestamp, a.order) < std::tie(b.timestamp, b.order); });
  lcm::LogFile log(path, "w");
  if (!log.good()) throw std::runtime_error("cannot write " + path);
  for (auto& e : events) {
    lcm::LogEvent le;
    le.eventnum = 0;
    le.timestamp = e.timestamp;
    le.channel = e.channel;
    le.datalen = static_cast<int32_t>(e.bytes.size());
    le.data = e.bytes.data();
    if (log.writeEvent(&le) != 0) throw std::runtime_error("cannot write an event to " + path);
  }
  return static_cast<int64_t>(events.size());
}

}  // namespace gpilot::test
