#include "message_checks.hpp"

#include <cmath>
#include <cstdio>
#include <initializer_list>

namespace gpilot {
namespace {

// The first non-finite value among named float fields, as a reason; "" if all are finite.
struct Finite {
  std::string reason;
  template <class T>
  Finite& operator()(const char* name, const T* v, int n) {
    for (int i = 0; reason.empty() && i < n; ++i)
      if (!std::isfinite(v[i])) reason = std::string(name) + " is not finite";
    return *this;
  }
  Finite& operator()(const char* name, float v) { return (*this)(name, &v, 1); }
  Finite& operator()(const char* name, double v) { return (*this)(name, &v, 1); }
};

std::string check_enum(const char* name, int value, int lo, int hi) {
  if (value < lo || value > hi) return std::string(name) + " " + std::to_string(value) + " is not a known value";
  return "";
}

std::string check_box(const char* name, const float* box) {
  if (box[2] < 0 || box[3] < 0) return std::string(name) + " has a negative size";
  return "";
}

// An optional box: all zero for none, else a box with an area inside a width x height image. The float edges
// may pass the image's by 0.01 px (a box clipped to the image in double, sent as float).
std::string check_optional_box_in_image(const char* name, const float* box, int width, int height) {
  if (box[0] == 0 && box[1] == 0 && box[2] == 0 && box[3] == 0) return "";
  if (box[2] <= 0 || box[3] <= 0) return std::string(name) + " is neither all zero nor a box with an area";
  constexpr double kSlack = 0.01;
  if (box[0] < -kSlack || box[1] < -kSlack || static_cast<double>(box[0]) + box[2] > width + kSlack ||
      static_cast<double>(box[1]) + box[3] > height + kSlack)
    return std::string(name) + " is outside the " + std::to_string(width) + "x" + std::to_string(height) + " image";
  return "";
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The box of a tracked user in an image_width x image_height image (0: not known, any image): each side at
// least a pixel and at most kMaxBoxInImages image sizes, its corner at most that far off the image. Finite
// values are assumed (checked first).
std::string check_user_box(const char* name, const float* box, int image_width, int image_height) {
  const double image[2] = {static_cast<double>(image_width > 0 ? image_width : kMaxImageSide),
                           static_cast<double>(image_height > 0 ? image_height : kMaxImageSide)};
  const char* corner[2] = {"x", "y"};
  const char* side[2] = {"width", "height"};
  const auto where = [&](int i) {
    return image_width > 0 ? std::to_string(static_cast<int>(image[i])) + " px image" : std::string("any image");
  };
  for (int i = 0; i < 2; ++i) {
    const double s = box[2 + i];
    if (s < kMinBoxSide) return std::string(name) + " " + side[i] + " " + number(s) + " is below a pixel";
    if (s > kMaxBoxInImages * image[i])
      return std::string(name) + " " + side[i] + " " + number(s) + " is beyond " + where(i) + " (" +
             number(kMaxBoxInImages) + " x)";
  }
  for (int i = 0; i < 2; ++i) {
    const double c = box[i];
    if (c < -kMaxBoxInImages * image[i] || c > (1 + kMaxBoxInImages) * image[i])
      return std::string(name) + " " + corner[i] + " " + number(c) + " is far outside " + where(i);
  }
  return "";
}

// A track's user box: a box by check_user_box, or all zero while searching (no user yet). Decide copies the
// width of any box into its command, so a searching track's box is held to the same rules.
// A box is only meaningful in an image of known size (hands publishes the box with its frame's size: the
// fuzzer found a track without one whose box then failed decide's check).
std::string check_track_box(const char* name, const float* box, int status, int image_width, int image_height) {
  if (status == user_track_t::STATUS_SEARCHING && box[0] == 0 && box[1] == 0 && box[2] == 0 && box[3] == 0) return "";
  if (image_width <= 0 || image_height <= 0) return std::string(name) + " without an image size";
  return check_user_box(name, box, image_width, image_height);
}

std::string check_image_size(int width, int height) {
  if (width < 0 || height < 0) return "negative image size";
  if (width > kMaxImageSide || height > kMaxImageSide)
    return "image size " + std::to_string(width) + "x" + std::to_string(height) + " is larger than " +
           std::to_string(kMaxImageSide) + " pixels a side";
  return "";
}

std::string first(std::initializer_list<std::string> reasons) {
  for (const auto& r : reasons)
    if (!r.empty()) return r;
  return "";
}

}  // namespace

std::string check_message(const image_t& m) {
  if (m.size < 0 || static_cast<size_t>(m.size) != m.data.size()) return "image size field disagrees with its data";
  if (m.width <= 0 || m.height <= 0)
    return "image has no pixels (" + std::to_string(m.width) + "x" + std::to_string(m.height) + ")";
  if (m.width > kMaxImageSide || m.height > kMaxImageSide)
    return "image larger than " + std::to_string(kMaxImageSide) + " pixels a side";
  int bpp = 0;
  switch (m.pixel_format) {
    case image_t::PIXEL_FORMAT_GRAY8: bpp = 1; break;
    case image_t::PIXEL_FORMAT_BGR8: bpp = 3; break;
    case image_t::PIXEL_FORMAT_JPEG: return m.size > 0 ? "" : "empty JPEG";
    default: return "unknown pixel format " + std::to_string(m.pixel_format);
  }
  const int64_t row = static_cast<int64_t>(m.width) * bpp;
  if (m.row_stride < row)
    return "row stride " + std::to_string(m.row_stride) + " is less than width x " + std::to_string(bpp) + " bytes";
  const int64_t need = static_cast<int64_t>(m.row_stride) * (m.height - 1) + row;
  if (m.size < need)
    return "image data has " + std::to_string(m.size) + " bytes, " + std::to_string(m.width) + "x" +
           std::to_string(m.height) + " needs " + std::to_string(need);
  return "";
}

std::string check_message(const tracker_init_t& m) {
  return first({check_enum("command", m.command, tracker_init_t::COMMAND_SET_BOX, tracker_init_t::COMMAND_RESET),
                Finite()("box", m.box, 4).reason,
                m.command == tracker_init_t::COMMAND_SET_BOX && (m.box[2] <= 0 || m.box[3] <= 0)
                    ? "manual box has no area"
                    : "",
                m.command == tracker_init_t::COMMAND_SET_BOX ? check_user_box("box", m.box, 0, 0) : ""});
}

std::string check_message(const user_track_t& m) {
  return first({check_enum("status", m.status, user_track_t::STATUS_SEARCHING, user_track_t::STATUS_LOST),
                check_enum("init_source", m.init_source, user_track_t::INIT_NONE, user_track_t::INIT_PERSON),
                check_enum("facing", m.facing, user_track_t::FACING_UNKNOWN, user_track_t::FACING_AWAY),
                Finite()("box", m.box, 4)("confidence", m.confidence)("face_box", m.face_box, 4).reason,
                check_box("box", m.box), check_box("face_box", m.face_box),
                check_image_size(m.image_width, m.image_height),
                check_track_box("box", m.box, m.status, m.image_width, m.image_height),
                check_optional_box_in_image("face_box", m.face_box, m.image_width, m.image_height)});
}

std::string check_message(const hand_obs_t& m) {
  bool visibility_ok = true;
  for (const auto& l : m.pose_landmarks) visibility_ok = visibility_ok && l[3] >= 0 && l[3] <= 1;
  return first({check_enum("kind", m.kind, hand_obs_t::KIND_NONE, hand_obs_t::KIND_FRONT),
                check_enum("method", m.method, hand_obs_t::METHOD_SKIN, hand_obs_t::METHOD_POSE),
                check_enum("track_status", m.track_status, user_track_t::STATUS_SEARCHING, user_track_t::STATUS_LOST),
                Finite()("user_box", m.user_box, 4)("shoulder_centre", m.shoulder_centre, 2)(
                    "body_centre", m.body_centre, 2)("vector", m.vector, 2)("hand_box", m.hand_box, 4)(
                    "pose_score", m.pose_score)("pose_landmarks", &m.pose_landmarks[0][0], 33 * 4)
                    .reason,
                check_box("user_box", m.user_box), check_box("hand_box", m.hand_box),
                check_image_size(m.image_width, m.image_height),
                check_track_box("user_box", m.user_box, m.track_status, m.image_width, m.image_height),
                m.hand_skin < 0 || m.skin_outside < 0 || m.skin_inside < 0 ? "negative skin count" : "",
                m.skin_user_samples < 0 || m.skin_scene_samples < 0 ? "negative skin sample count" : "",
                !(m.skin_changed >= 0 && m.skin_changed <= 1) ? "skin_changed not in 0..1" : "",
                !(m.pose_score >= 0 && m.pose_score <= 1) ? "pose_score not in 0..1" : "",
                visibility_ok ? "" : "a pose landmark's visibility is not in 0..1"});
}

std::string check_message(const gesture_cmd_t& m) {
  return first({check_enum("mode", m.mode, gesture_cmd_t::MODE_HOVER, gesture_cmd_t::MODE_FURTHER),
                Finite()("direction", m.direction, 3)("user_box_width", m.user_box_width).reason,
                m.user_box_width < 0 ? "negative user box width" : "",
                m.user_box_width > 0 && m.user_box_width < kMinBoxSide
                    ? "user_box_width " + number(m.user_box_width) + " is below a pixel"
                    : "",
                m.user_box_width > kMaxBoxInImages * kMaxImageSide
                    ? "user_box_width " + number(m.user_box_width) + " is beyond any image"
                    : "",
                m.n_out < 0 || m.n_front_higher < 0 || m.n_front_lower < 0 || m.buffer_fill < 0
                    ? "negative buffer count"
                    : ""});
}

std::string check_message(const flight_control_t& m) {
  return first({check_enum("command", m.command, flight_control_t::COMMAND_ENGAGE, flight_control_t::COMMAND_DISARM),
                Finite()("takeoff_altitude", m.takeoff_altitude).reason});
}

std::string check_message(const flight_setpoint_t& m) {
  return first({check_enum("mode", m.mode, gesture_cmd_t::MODE_HOVER, gesture_cmd_t::MODE_FURTHER),
                Finite()("velocity", m.velocity, 3)("yaw_rate", m.yaw_rate).reason});
}

std::string check_message(const vehicle_state_t& m) {
  return first({check_enum("source", m.source, vehicle_state_t::SOURCE_SIMULATOR, vehicle_state_t::SOURCE_MAVLINK),
                check_enum("landed_state", m.landed_state, vehicle_state_t::LANDED_UNKNOWN,
                           vehicle_state_t::LANDED_LANDING),
                Finite()("position", m.position, 3)("velocity", m.velocity, 3)("attitude", m.attitude, 3)(
                    "yaw_rate", m.yaw_rate)
                    .reason});
}

std::string check_message(const autopilot_t& m) {
  constexpr int64_t kMaxCustomMode = 0xFFFFFFFFLL;  // MAVLink's custom_mode is a uint32
  constexpr size_t kMaxParamIdLength = 16;          // MAVLink's param_id is char[16]
  constexpr int kMavStateMax = 8;                   // MAV_STATE_FLIGHT_TERMINATION
  constexpr int kMavParamTypeMax = 10;              // MAV_PARAM_TYPE_REAL64
  return first({check_enum("kind", m.kind, autopilot_t::KIND_HEARTBEAT, autopilot_t::KIND_PARAM_VALUE),
                check_enum("base_mode", m.base_mode, 0, 255), check_enum("system_status", m.system_status, 0, kMavStateMax),
                check_enum("param_type", m.param_type, 0, kMavParamTypeMax),
                m.custom_mode < 0 || m.custom_mode > kMaxCustomMode ? "custom_mode not in 0..2^32-1" : "",
                m.param_id.size() > kMaxParamIdLength ? "param_id longer than 16 characters" : "",
                Finite()("param_value", m.param_value).reason});
}

std::string check_message(const ground_truth_t& m) {
  return first({check_enum("gesture", m.gesture, ground_truth_t::GESTURE_REST, ground_truth_t::GESTURE_FURTHER),
                check_enum("expected_kind", m.expected_kind, hand_obs_t::KIND_NONE, hand_obs_t::KIND_FRONT),
                check_enum("expected_mode", m.expected_mode, gesture_cmd_t::MODE_HOVER, gesture_cmd_t::MODE_FURTHER),
                Finite()("user_box", m.user_box, 4)("face_box", m.face_box, 4)("shoulder_centre", m.shoulder_centre,
                                                                                 2)("body_centre", m.body_centre, 2)(
                    "left_hand", m.left_hand, 2)("right_hand", m.right_hand, 2)("hand_size", m.hand_size)(
                    "expected_vector", m.expected_vector, 2)("expected_direction", m.expected_direction, 3)(
                    "person_position", m.person_position, 3)("camera_position", m.camera_position, 3)(
                    "camera_yaw", m.camera_yaw)
                    .reason});
}

std::string check_message(const health_t& m) {
  return first({check_enum("state", m.state, health_t::STATE_STARTING, health_t::STATE_STOPPING),
                Finite()("rate_in_hz", m.rate_in_hz)("rate_out_hz", m.rate_out_hz)(
                    "processing_ms_p50", m.processing_ms_p50)("processing_ms_p99", m.processing_ms_p99)("cpu_s", m.cpu_s)
                    .reason,
                m.cpu_s < 0 ? "cpu_s " + number(m.cpu_s) + " is negative" : ""});
}

std::string check_message(const config_t& m) {
  if (m.process.empty()) return "process is empty";
  if (m.yaml.empty()) return "yaml is empty";
  return "";
}

}  // namespace gpilot
