// Scenario files: parsing, checking (every error names the file and the key) and the smooth script.
#include "scenario.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "gpilot/ground_truth_t.hpp"
#include "paths.hpp"
#include "person_figure.hpp"

namespace gpilot {
namespace {

constexpr double kDeg = M_PI / 180.0;

const char* const kGestureNames[] = {"REST", "OUT", "UP", "DOWN", "CLOSER", "FURTHER"};
static_assert(ground_truth_t::GESTURE_REST == 0 && ground_truth_t::GESTURE_OUT == 1 && ground_truth_t::GESTURE_UP == 2 &&
                  ground_truth_t::GESTURE_DOWN == 3 && ground_truth_t::GESTURE_CLOSER == 4 &&
                  ground_truth_t::GESTURE_FURTHER == 5,
              "kGestureNames follows ground_truth_t::GESTURE_*");

class Reader {
 public:
  explicit Reader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    throw ScenarioError(origin_ + ": " + key + ": " + why);
  }

  double number(const YAML::Node& n, const std::string& key, double min, double max) const {
    double v = 0.0;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(key, "not a number");
    }
    if (!std::isfinite(v) || v < min || v > max)
      fail(key, "value " + n.Scalar() + " outside [" + fmt(min) + ", " + fmt(max) + "]");
    return v;
  }

  void opt(const YAML::Node& map, const char* name, const std::string& ctx, double& out, double min, double max) const {
    if (const YAML::Node n = map[name]) out = number(n, ctx + "." + name, min, max);
  }

  std::string text(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) fail(key, "not a string");
    return n.Scalar();
  }

  std::array<int, 3> colour(const YAML::Node& n, const std::string& key) const {
    if (!n.IsSequence() || n.size() != 3) fail(key, "a colour is [b, g, r]");
    std::array<int, 3> c{};
    for (size_t i = 0; i < 3; ++i) c[i] = static_cast<int>(number(n[i], key, 0, 255));
    return c;
  }

  void only(const YAML::Node& map, const std::string& ctx, std::initializer_list<const char*> keys) const {
    if (!map.IsMap()) fail(ctx, "must be a map");
    for (const auto& kv : map) {
      const std::string k = kv.first.Scalar();
      if (std::none_of(keys.begin(), keys.end(), [&](const char* a) { return k == a; }))
        fail(ctx.empty() ? k : ctx + "." + k, "unknown key");
    }
  }

  bool boolean(const YAML::Node& n, const std::string& key) const {
    try {
      return n.as<bool>();
    } catch (const YAML::Exception&) {
      fail(key, "true or false");
    }
  }

  static std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

 private:
  std::string origin_;
};

ArmPose read_arm(const Reader& r, const YAML::Node& n, const std::string& key, const ArmPose& previous) {
  try {
    if (n.IsScalar()) return ArmPose::preset(n.Scalar());
  } catch (const ScenarioError& e) {
    r.fail(key, e.what());
  }
  r.only(n, key, {"preset", "angle_deg", "extension", "forward_deg", "hand"});
  if (const YAML::Node h = n["hand"]) {
    if (n.size() != 1) r.fail(key, "`hand` cannot be combined with other keys");
    if (!h.IsSequence() || h.size() != 3) r.fail(key + ".hand", "is [out, up, forward] metres");
    return ArmPose::from_hand_offset(r.number(h[0], key + ".hand", -2, 2), r.number(h[1], key + ".hand", -2, 2),
                                     r.number(h[2], key + ".hand", -2, 2));
  }
  ArmPose p = previous;
  if (const YAML::Node pre = n["preset"]) {
    try {
      p = ArmPose::preset(r.text(pre, key + ".preset"));
    } catch (const ScenarioError& e) {
      r.fail(key + ".preset", e.what());
    }
  }
  r.opt(n, "angle_deg", key, p.angle_deg, -180, 200);
  r.opt(n, "extension", key, p.extension, 0.3, 1.0);
  r.opt(n, "forward_deg", key, p.forward_deg, -30, 90);
  return p;
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

double mix(double a, double b, double w) { return a + (b - a) * w; }

ArmPose mix(const ArmPose& a, const ArmPose& b, double w) {
  return {mix(a.angle_deg, b.angle_deg, w), mix(a.extension, b.extension, w), mix(a.forward_deg, b.forward_deg, w)};
}

ScenarioState mix(const ScenarioState& a, const ScenarioState& b, double w) {
  ScenarioState s = w >= 0.5 ? b : a;  // discrete values switch half-way
  s.right_arm = mix(a.right_arm, b.right_arm, w);
  s.left_arm = mix(a.left_arm, b.left_arm, w);
  s.step_m = mix(a.step_m, b.step_m, w);
  s.turn_deg = mix(a.turn_deg, b.turn_deg, w);
  s.light = mix(a.light, b.light, w);
  s.shake_deg = mix(a.shake_deg, b.shake_deg, w);
  s.noise_sigma = mix(a.noise_sigma, b.noise_sigma, w);
  s.blur_px = mix(a.blur_px, b.blur_px, w);
  return s;
}

BystanderState mix(const BystanderState& a, const BystanderState& b, double w) {
  BystanderState s = b;
  s.north = mix(a.north, b.north, w);
  s.east = mix(a.east, b.east, w);
  s.right_arm = mix(a.right_arm, b.right_arm, w);
  s.left_arm = mix(a.left_arm, b.left_arm, w);
  s.wave_deg = mix(a.wave_deg, b.wave_deg, w);
  s.wave_hz = mix(a.wave_hz, b.wave_hz, w);
  return s;
}

template <class K>
double progress(const K& k, double t) {
  return k.transition_s <= 0.0 ? (t >= k.t_s ? 1.0 : 0.0) : smoothstep((t - k.t_s) / k.transition_s);
}

}  // namespace

ArmPose ArmPose::preset(const std::string& name) {
  if (name == "rest") return {0.0, 1.0, 6.0};
  if (name == "out") return {90.0, 1.0, 0.0};
  if (name == "up") return {160.0, 0.9, 0.0};  // bent a little: the hand stays in the hands stage's search rectangle
  // Straight, out and down: 50 deg from down is DOWN by decide's lambda4 (up to 63 deg), and far enough from a
  // hanging arm that a person reads it as a gesture (the real photos' keypoint truth calls a straight arm within
  // 45 deg of down at rest).
  if (name == "down") return {50.0, 1.0, 0.0};
  // In front of the chest (above the body centre) and in front of the belly (below it, above the hips), near the
  // midline. The low hand is held near the belly: seen from a drone above the user, a hand further forward
  // projects lower (0.25 m forward at 2.4 m from a drone 1 m above the hand: on the hip line, where a hand is
  // at rest).
  if (name == "front_high") return from_hand_offset(-0.14, -0.14, 0.30);
  if (name == "front_low") return from_hand_offset(-0.14, -0.36, 0.15);
  throw ScenarioError("unknown arm preset '" + name + "' (rest, out, up, down, front_high, front_low)");
}

ArmPose ArmPose::from_hand_offset(double out, double up, double forward) {
  const double r = std::sqrt(out * out + up * up + forward * forward);
  ArmPose p;
  p.extension = std::clamp(r / FigureDims{}.arm_length(), 0.3, 1.0);
  p.forward_deg = r > 0 ? std::asin(std::clamp(forward / r, -1.0, 1.0)) / kDeg : 0.0;
  p.angle_deg = std::atan2(out, -up) / kDeg;
  return p;
}

int gesture_from_name(const std::string& name) {
  for (int i = 0; i < 6; ++i)
    if (name == kGestureNames[i]) return i;
  return -1;
}

const char* gesture_name(int gesture) { return gesture >= 0 && gesture < 6 ? kGestureNames[gesture] : "?"; }

Scenario Scenario::load(const std::string& path_or_name) {
  std::string path = path_or_name;
  const bool bare = path.find('/') == std::string::npos && path.find('.') == std::string::npos;
  if (bare) path = "deploy/scenarios/" + path + ".yaml";
  path = resolve_project_path(path);
  std::ifstream in(path);
  if (!in) throw ScenarioError("cannot open scenario '" + path_or_name + "' (" + path + ")");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

Scenario Scenario::parse(const std::string& yaml, const std::string& origin) {
  const Reader r(origin);
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(origin + ": not valid YAML: " + e.what());
  }
  r.only(root, "", {"name", "description", "duration_s", "background", "background_grade", "transition_s", "camera",
                    "person", "distractor", "wall", "bystanders", "keyframes"});
  Scenario s;
  s.origin_ = origin;
  if (root["name"]) s.name_ = r.text(root["name"], "name");
  if (root["description"]) s.description_ = r.text(root["description"], "description");
  if (root["background"]) s.background_ = r.text(root["background"], "background");
  if (const YAML::Node g = root["background_grade"]) {
    r.only(g, "background_grade", {"saturation", "red_gain", "blue_gain", "blur_sigma"});
    r.opt(g, "blur_sigma", "background_grade", s.grade_.blur_sigma, 0.0, 20.0);
    r.opt(g, "saturation", "background_grade", s.grade_.saturation, 0.0, 2.0);
    r.opt(g, "red_gain", "background_grade", s.grade_.red_gain, 0.0, 4.0);
    r.opt(g, "blue_gain", "background_grade", s.grade_.blue_gain, 0.0, 4.0);
  }
  double transition = 1.0;
  r.opt(root, "transition_s", "", transition, 0.0, 600.0);

  if (const YAML::Node c = root["camera"]) {
    r.only(c, "camera", {"north", "east", "down", "yaw_deg"});
    double yaw_deg = 0.0;
    r.opt(c, "north", "camera", s.camera_.north, -1e4, 1e4);
    r.opt(c, "east", "camera", s.camera_.east, -1e4, 1e4);
    r.opt(c, "down", "camera", s.camera_.down, -1e4, 1e4);
    r.opt(c, "yaw_deg", "camera", yaw_deg, -360, 360);
    s.camera_.yaw = yaw_deg * kDeg;
  }
  // Default: the person stands 3 m in front of the camera, facing it.
  s.person_.north = s.camera_.north + 3.0 * std::cos(s.camera_.yaw);
  s.person_.east = s.camera_.east + 3.0 * std::sin(s.camera_.yaw);
  bool facing_given = false;
  if (const YAML::Node p = root["person"]) {
    r.only(p, "person", {"north", "east", "facing_yaw_deg", "skin_tone", "shirt_bgr", "trousers_bgr", "sleeves", "tint_face"});
    r.opt(p, "north", "person", s.person_.north, -1e4, 1e4);
    r.opt(p, "east", "person", s.person_.east, -1e4, 1e4);
    if (const YAML::Node f = p["facing_yaw_deg"]) {
      s.person_.facing_yaw = r.number(f, "person.facing_yaw_deg", -360, 360) * kDeg;
      s.person_.faces_camera = false;
      facing_given = true;
    }
    if (p["skin_tone"]) s.person_.skin_tone = r.text(p["skin_tone"], "person.skin_tone");
    if (p["shirt_bgr"]) s.person_.shirt_bgr = r.colour(p["shirt_bgr"], "person.shirt_bgr");
    if (p["trousers_bgr"]) s.person_.trousers_bgr = r.colour(p["trousers_bgr"], "person.trousers_bgr");
    if (p["sleeves"]) {
      const std::string v = r.text(p["sleeves"], "person.sleeves");
      if (v != "short" && v != "long") r.fail("person.sleeves", "short or long, not '" + v + "'");
      s.person_.long_sleeves = v == "long";
    }
    if (p["tint_face"]) s.person_.tint_face = r.boolean(p["tint_face"], "person.tint_face");
  }
  if (!facing_given)
    s.person_.facing_yaw = std::atan2(s.camera_.east - s.person_.east, s.camera_.north - s.person_.north);
  if (const YAML::Node d = root["distractor"]) {
    r.only(d, "distractor", {"left", "up", "behind", "radius"});
    r.opt(d, "left", "distractor", s.distractor_.left, -50, 50);
    r.opt(d, "up", "distractor", s.distractor_.up, -5, 50);
    r.opt(d, "behind", "distractor", s.distractor_.behind, 0.2, 100);
    r.opt(d, "radius", "distractor", s.distractor_.radius, 0.01, 5);
  }

  if (const YAML::Node w = root["wall"]) {
    r.only(w, "wall", {"distance_m", "bgr", "texture", "width_m", "height_m", "shading"});
    s.wall_.present = true;
    r.opt(w, "distance_m", "wall", s.wall_.distance_m, 0.1, 100);
    if (w["bgr"]) s.wall_.bgr = r.colour(w["bgr"], "wall.bgr");
    if (w["texture"]) {
      s.wall_.texture = r.text(w["texture"], "wall.texture");
      if (s.wall_.texture != "plaster" && s.wall_.texture != "wood" && s.wall_.texture != "flat")
        r.fail("wall.texture", "plaster, wood or flat, not '" + s.wall_.texture + "'");
    }
    r.opt(w, "width_m", "wall", s.wall_.width_m, 0, 1000);
    r.opt(w, "height_m", "wall", s.wall_.height_m, 0, 100);
    r.opt(w, "shading", "wall", s.wall_.shading, 0, 0.8);
  }

  if (const YAML::Node list = root["bystanders"]) {
    if (!list.IsSequence()) r.fail("bystanders", "a list of people");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string ctx = "bystanders[" + std::to_string(i) + "]";
      const YAML::Node b = list[i];
      r.only(b, ctx, {"name", "shirt_bgr", "trousers_bgr", "sleeves", "keyframes"});
      Bystander by;
      by.name = b["name"] ? r.text(b["name"], ctx + ".name") : "bystander " + std::to_string(i + 1);
      by.look.shirt_bgr = {40, 45, 140};
      by.look.trousers_bgr = {50, 50, 50};
      if (b["shirt_bgr"]) by.look.shirt_bgr = r.colour(b["shirt_bgr"], ctx + ".shirt_bgr");
      if (b["trousers_bgr"]) by.look.trousers_bgr = r.colour(b["trousers_bgr"], ctx + ".trousers_bgr");
      if (b["sleeves"]) {
        const std::string v = r.text(b["sleeves"], ctx + ".sleeves");
        if (v != "short" && v != "long") r.fail(ctx + ".sleeves", "short or long, not '" + v + "'");
        by.look.long_sleeves = v == "long";
      }
      const YAML::Node bk = b["keyframes"];
      if (!bk || !bk.IsSequence() || bk.size() == 0) r.fail(ctx + ".keyframes", "a non-empty list is required");
      BystanderState st;
      st.right_arm = st.left_arm = ArmPose::preset("rest");
      for (size_t k = 0; k < bk.size(); ++k) {
        const std::string kc = ctx + ".keyframes[" + std::to_string(k) + "]";
        const YAML::Node n = bk[k];
        r.only(n, kc, {"t", "transition_s", "north", "east", "right_arm", "left_arm", "wave_deg", "wave_hz"});
        BystanderKeyframe kf;
        if (!n["t"]) r.fail(kc + ".t", "missing");
        kf.t_s = r.number(n["t"], kc + ".t", 0, 1e6);
        if (!by.keyframes.empty() && kf.t_s <= by.keyframes.back().t_s) r.fail(kc + ".t", "times must increase");
        if (k == 0 && (!n["north"] || !n["east"])) r.fail(kc, "the first keyframe says where they stand (north, east)");
        kf.transition_s = transition;
        r.opt(n, "transition_s", kc, kf.transition_s, 0.0, 600.0);
        r.opt(n, "north", kc, st.north, -1e4, 1e4);
        r.opt(n, "east", kc, st.east, -1e4, 1e4);
        if (n["right_arm"]) st.right_arm = read_arm(r, n["right_arm"], kc + ".right_arm", st.right_arm);
        if (n["left_arm"]) st.left_arm = read_arm(r, n["left_arm"], kc + ".left_arm", st.left_arm);
        r.opt(n, "wave_deg", kc, st.wave_deg, 0, 90);
        r.opt(n, "wave_hz", kc, st.wave_hz, 0.05, 10);
        kf.state = st;
        by.keyframes.push_back(kf);
      }
      by.starts.assign(by.keyframes.size(), by.keyframes.front().state);
      for (size_t k = 2; k < by.keyframes.size(); ++k)
        by.starts[k] = mix(by.starts[k - 1], by.keyframes[k - 1].state, progress(by.keyframes[k - 1], by.keyframes[k].t_s));
      s.bystanders_.push_back(std::move(by));
    }
  }

  const YAML::Node keys = root["keyframes"];
  if (!keys || !keys.IsSequence() || keys.size() == 0) r.fail("keyframes", "a non-empty list is required");
  ScenarioState state;
  state.right_arm = state.left_arm = ArmPose::preset("rest");
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string ctx = "keyframes[" + std::to_string(i) + "]";
    const YAML::Node k = keys[i];
    r.only(k, ctx, {"t", "transition_s", "gesture", "right_arm", "left_arm", "step_m", "turn_deg", "light", "shake_deg",
                    "noise_sigma", "blur_px", "jpeg_quality", "distractor"});
    Keyframe kf;
    if (!k["t"]) r.fail(ctx + ".t", "missing");
    kf.t_s = r.number(k["t"], ctx + ".t", 0, 1e6);
    if (!s.keyframes_.empty() && kf.t_s <= s.keyframes_.back().t_s) r.fail(ctx + ".t", "times must increase");
    kf.transition_s = transition;
    r.opt(k, "transition_s", ctx, kf.transition_s, 0.0, 600.0);
    if (const YAML::Node g = k["gesture"]) {
      state.gesture = gesture_from_name(r.text(g, ctx + ".gesture"));
      if (state.gesture < 0) r.fail(ctx + ".gesture", "one of REST OUT UP DOWN CLOSER FURTHER");
    }
    if (k["right_arm"]) state.right_arm = read_arm(r, k["right_arm"], ctx + ".right_arm", state.right_arm);
    if (k["left_arm"]) state.left_arm = read_arm(r, k["left_arm"], ctx + ".left_arm", state.left_arm);
    r.opt(k, "step_m", ctx, state.step_m, -20, 20);
    r.opt(k, "turn_deg", ctx, state.turn_deg, -360, 360);
    r.opt(k, "light", ctx, state.light, 0.05, 4.0);
    r.opt(k, "shake_deg", ctx, state.shake_deg, 0, 10);
    r.opt(k, "noise_sigma", ctx, state.noise_sigma, 0, 64);
    r.opt(k, "blur_px", ctx, state.blur_px, 0, 64);
    if (const YAML::Node q = k["jpeg_quality"]) state.jpeg_quality = static_cast<int>(r.number(q, ctx + ".jpeg_quality", 0, 100));
    if (const YAML::Node d = k["distractor"]) state.distractor = r.boolean(d, ctx + ".distractor");
    kf.state = state;
    s.keyframes_.push_back(kf);
  }
  // Each keyframe starts from wherever the previous one had got to when it began (no jump if interrupted).
  s.starts_.assign(s.keyframes_.size(), s.keyframes_.front().state);
  for (size_t k = 2; k < s.keyframes_.size(); ++k)
    s.starts_[k] = mix(s.starts_[k - 1], s.keyframes_[k - 1].state, progress(s.keyframes_[k - 1], s.keyframes_[k].t_s));
  const Keyframe& last = s.keyframes_.back();
  s.duration_s_ = last.t_s + last.transition_s + 2.0;
  r.opt(root, "duration_s", "", s.duration_s_, 0.04, 1e6);
  return s;
}

ScenarioState Scenario::state_at(double t_s) const {
  // The last keyframe that has begun moves from starts_[k] (where the script was when it began) to its state.
  size_t k = 0;
  while (k + 1 < keyframes_.size() && t_s >= keyframes_[k + 1].t_s) ++k;
  return k == 0 ? keyframes_.front().state : mix(starts_[k], keyframes_[k].state, progress(keyframes_[k], t_s));
}

BystanderState Bystander::state_at(double t_s) const {
  size_t k = 0;
  while (k + 1 < keyframes.size() && t_s >= keyframes[k + 1].t_s) ++k;
  BystanderState s = k == 0 ? keyframes.front().state : mix(starts[k], keyframes[k].state, progress(keyframes[k], t_s));
  if (s.wave_deg > 0.0) s.right_arm.angle_deg += s.wave_deg * std::sin(2.0 * M_PI * s.wave_hz * t_s);
  return s;
}

std::optional<double> Scenario::key_time_of(int gesture) const {
  const std::vector<double> times = key_times();
  for (size_t k = 0; k < times.size(); ++k)
    if (keyframes_[k].state.gesture == gesture) return times[k];
  return std::nullopt;
}

std::vector<double> Scenario::key_times() const {
  std::vector<double> out;
  for (size_t k = 0; k < keyframes_.size(); ++k) {
    const double arrive = k == 0 ? keyframes_[k].t_s : keyframes_[k].t_s + keyframes_[k].transition_s;
    const double next = k + 1 < keyframes_.size() ? keyframes_[k + 1].t_s : duration_s_;
    out.push_back(std::min(next, std::max(arrive, 0.5 * (arrive + next))));
  }
  return out;
}

}  // namespace gpilot
