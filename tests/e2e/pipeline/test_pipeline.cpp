// End to end: deploy/services.yaml run by gpilot-launch on each shipped scenario (real processes, real LCM, a
// private network namespace), then the recorded log is judged against the scenario's ground truth, gesture by
// gesture as the user made them, every frame from 0.8 s after each true change: the drone moves the way the
// user points (within 15°), climbs on UP, descends on DOWN, closes in on CLOSER, backs off on FURTHER, drifts
// < 10 cm at rest; no FLIGHT_SETPOINT flies a motion while the user rests; the annotated video is written (by the
// tour's run: gpilot-view's drawing and encoding take a third of a pipeline's CPU beside the pose net, and two
// pipelines share the 2 cores under ctest -j2). The
// decide stage's reaction, its frames still carrying the old command and its false commands are reported
// (gpilot-eval-decide's scoring). And each stage killed mid-run in turn: the setpoint is zero within 0.3 s, the stage is restarted,
// control resumes (after gpilot-flight, once the operator engages again).
//
// One ctest entry per scenario and per killed stage (tests/e2e/pipeline/CMakeLists.txt). The run's folder is
// removed when its test passes and kept (path printed) when it fails. GPILOT_E2E_LOG=FILE judges that log
// instead of flying (for working on the checks).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "box_iou.hpp"
#include "child_process.hpp"
#include "run_command.hpp"
#include "decide_eval.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"

namespace fs = std::filesystem;

namespace gpilot {
namespace {

struct Recorded {
  struct State { int64_t t; double n, e, d, yaw; };
  struct Truth { int64_t t; ground_truth_t m; };
  struct Setpoint { int64_t t; double speed; };
  std::vector<State> states;
  std::vector<Truth> truth;
  std::vector<Setpoint> setpoints;
  std::map<int64_t, ScoredCommand> commands;  // GESTURE_CMD by seq
  std::map<int64_t, user_track_t> tracks;     // USER_TRACK by seq
  std::map<std::string, std::vector<std::pair<int64_t, int32_t>>> health_pids;  // name -> (t, pid)
};

double speed(const flight_setpoint_t& m) { return std::hypot(m.velocity[0], m.velocity[1], m.velocity[2]); }

// All times are the logger's receive times (wall clock, µs), so they compare across processes.
Recorded read_log(const std::string& path) {
  Recorded r;
  lcm::LogFile log(path, "r");
  EXPECT_TRUE(log.good()) << path;
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev; ev = log.readNextEvent()) {
    const std::string ch = ev->channel;
    if (ch == "VEHICLE_STATE") {
      vehicle_state_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0)
        r.states.push_back({ev->timestamp, m.position[0], m.position[1], m.position[2], m.attitude[2]});
    } else if (ch == "GROUND_TRUTH") {
      ground_truth_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) r.truth.push_back({ev->timestamp, m});
    } else if (ch == "FLIGHT_SETPOINT") {
      flight_setpoint_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0)
        r.setpoints.push_back({ev->timestamp, speed(m)});
    } else if (ch == "GESTURE_CMD") {
      gesture_cmd_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) r.commands[m.seq] = {m.mode, {m.direction[0], m.direction[1]}};
    } else if (ch == "USER_TRACK") {
      user_track_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) r.tracks[m.seq] = m;
    } else if (ch == "HEALTH") {
      health_t m{};
      if (m.decode(ev->data, 0, ev->datalen) > 0) r.health_pids[m.name].push_back({ev->timestamp, m.pid});
    }
  }
  return r;
}

// The services' default bus (GPILOT_LCM_URL is not set in the test's namespace).
const char* kLcmUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Waits (up to timeout_s) until FLIGHT_SETPOINT has asked for motion for hold_s without a break: the drone is
// flying on gestures. Start-up time varies with the machine's load, so a fixed delay does not say this.
bool wait_until_flying(double hold_s, double timeout_s) {
  lcm::LCM bus(kLcmUrl);
  if (!bus.good()) return false;
  int64_t moving_since = 0;
  struct Handler {
    int64_t* since;
    void on(const lcm::ReceiveBuffer*, const std::string&, const flight_setpoint_t* m) {
      const bool moving = speed(*m) > 0.05;
      if (!moving) *since = 0;
      else if (!*since) *since = wall_utime();
    }
  } handler{&moving_since};
  bus.subscribe("FLIGHT_SETPOINT", &Handler::on, &handler);
  const int64_t deadline = wall_utime() + static_cast<int64_t>(timeout_s * 1e6);
  while (wall_utime() < deadline) {
    bus.handleTimeout(50);
    if (moving_since && wall_utime() - moving_since > static_cast<int64_t>(hold_s * 1e6)) return true;
  }
  return false;
}

// The operator's part after gpilot-flight was killed at killed_at: once HEALTH comes from gpilot-flight again
// (a new process) and it has published zero setpoints for a while (it came up disengaged), and no earlier than
// 0.5 s after the kill (a person does not re-engage within the 0.3 s the test judges), sends FLIGHT_CONTROL engage
// three times. Engaging the moment HEALTH appears raced the judged setpoint when the restart was quick.
bool engage_when_flight_is_back(int64_t killed_at, double timeout_s) {
  lcm::LCM bus(kLcmUrl);
  if (!bus.good()) return false;
  struct Handler {
    bool back = false;
    int zero_setpoints = 0;
    void on_health(const lcm::ReceiveBuffer*, const std::string&, const health_t* m) {
      back = back || m->name == "gpilot-flight";
    }
    void on_setpoint(const lcm::ReceiveBuffer*, const std::string&, const flight_setpoint_t* m) {
      if (!back) return;
      if (speed(*m) == 0.0) ++zero_setpoints;
    }
  } handler;
  bus.subscribe("HEALTH", &Handler::on_health, &handler);
  bus.subscribe("FLIGHT_SETPOINT", &Handler::on_setpoint, &handler);
  const int64_t deadline = wall_utime() + static_cast<int64_t>(timeout_s * 1e6);
  auto ready = [&] { return handler.zero_setpoints >= 5 && wall_utime() >= killed_at + 500'000; };
  while (!ready() && wall_utime() < deadline) bus.handleTimeout(50);
  if (!ready()) return false;
  flight_control_t fc{};
  fc.utime = wall_utime();
  fc.command = flight_control_t::COMMAND_ENGAGE;
  fc.source = "test_pipeline_e2e";
  for (int i = 0; i < 3; ++i, usleep(200'000)) bus.publish("FLIGHT_CONTROL", &fc);
  return true;
}

// Runs the pipeline on a scenario into dir; returns the log path. kill_stage: SIGKILL it once the drone has
// flown on gestures for a second, and its wall time goes to *killed_at.
std::string run_pipeline(const std::string& scenario, const std::string& dir, double duration_s,
                         const std::string& kill_stage = "", int64_t* killed_at = nullptr,
                         const std::string& config_name = "synthetic", bool video = false) {
  fs::create_directories(dir);
  const std::string log = dir + "/log.lcmlog";
  const std::string src = GPILOT_SOURCE_DIR;
  const std::string config = src + "/deploy/config/" + config_name + ".yaml";
  test::ChildProcess launch({std::string(GPILOT_BIN_DIR) + "/gpilot-launch", "--services", src + "/deploy/services.yaml",
                             "--engage", "--duration", std::to_string(duration_s),
                             "--var", "config=" + config,
                             "--var", "source_flag=--synthetic",
                             "--var", "source=" + src + "/deploy/scenarios/" + scenario + ".yaml",
                             "--var", "capture_extra=", "--var", "backend=sim",
                             "--var", "mavlink=udp:127.0.0.1:14580", "--var", "log=" + log,
                             "--var", "video_out=" + (video ? dir + "/annotated.mp4" : std::string())});
  if (!kill_stage.empty()) {
    EXPECT_TRUE(wait_until_flying(1.0, duration_s / 2)) << "the drone never flew: nothing to interrupt";
    // Only this run's stage, a child of this run's gpilot-launch: ctest -j2 runs other pipelines beside it (in
    // their own network namespaces, but not their own PID namespaces).
    const std::string cmd = "pkill -KILL -P " + std::to_string(launch.pid()) + " -x " + kill_stage.substr(0, 15);
    EXPECT_EQ(std::system(cmd.c_str()), 0) << "could not kill " << kill_stage;
    const int64_t killed = wall_utime();  // pkill has returned: the stage is dead
    if (killed_at) *killed_at = killed;
    // A restarted flight stage comes up disengaged: the operator engages again (as gpilot-ctl would).
    if (kill_stage == "gpilot-flight") {
      EXPECT_TRUE(engage_when_flight_is_back(killed, 10.0)) << "gpilot-flight never came back disengaged";
    }
  }
  const int status = launch.wait();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "gpilot-launch failed on " << scenario;
  return log;
}

// The vehicle state at or just after t.
std::optional<Recorded::State> state_at(const Recorded& r, int64_t t) {
  const auto it = std::lower_bound(r.states.begin(), r.states.end(), t,
                                   [](const Recorded::State& s, int64_t v) { return s.t < v; });
  if (it == r.states.end()) return std::nullopt;
  return *it;
}

// The true gestures, cut as gpilot-eval-decide cuts them (decide_eval.hpp: a gesture, or a piece of an OUT
// gesture turned by more than 30°; the arm on its way belongs to where it arrives), in log time.
std::vector<TruthFrame> truth_frames(const Recorded& r) {
  std::vector<TruthFrame> t;
  for (const auto& f : r.truth)
    t.push_back({f.t, f.m.gesture, f.m.expected_mode, {f.m.expected_direction[0], f.m.expected_direction[1]}});
  return t;
}

// One GESTURE_CMD per truth frame (matched by seq; none: HOVER).
std::vector<ScoredCommand> commands_per_frame(const Recorded& r) {
  std::vector<ScoredCommand> c;
  for (const auto& f : r.truth) {
    const auto it = r.commands.find(f.m.seq);
    c.push_back(it == r.commands.end() ? ScoredCommand{} : it->second);
  }
  return c;
}

const char* kGestureNames[] = {"REST", "OUT", "UP", "DOWN", "CLOSER", "FURTHER"};

// Camera frame (x right, y down, z forward) to world NED, for a level camera with the vehicle's yaw.
void camera_to_world(const float c[3], double yaw, double w[3]) {
  w[0] = std::cos(yaw) * c[2] - std::sin(yaw) * c[0];
  w[1] = std::sin(yaw) * c[2] + std::cos(yaw) * c[0];
  w[2] = c[1];
}

struct Judged { int checked = 0; std::map<int, int> per_gesture; Score decide; };

// Judges every true gesture long enough to act on that the camera can see (a gesture whose arm is out of view is
// reported, not judged) on every frame from 0.8 s after it starts to its end (the decide stage reacts within
// 0.5 s, median, and the flight stage's 0.3 s command spacing may hold a change a little longer).
// open_findings: gestures that may be missed (an open finding, said where the scenario is listed), judged only
// for not flying the other way.
Judged judge_gestures(const Recorded& r, double rest_drift_m, const std::vector<int>& open_findings) {
  const auto kSettle = static_cast<int64_t>(ScoreRules{}.judged_after_s * 1e6);
  constexpr int64_t kMinJudged = 800'000;
  Judged j;
  const auto truth = truth_frames(r);
  const auto commands = commands_per_frame(r);
  j.decide = score_commands(truth, commands, ScoreRules{});
  const auto segments = truth_segments(truth, ScoreRules{});
  for (size_t k = 0; k < segments.size(); ++k) {
    const TruthSegment& seg = segments[k];
    const int gesture = truth[seg.begin].gesture;
    const int64_t from = truth[seg.begin].utime + kSettle, to = truth[seg.end - 1].utime;
    if (to - from < kMinJudged) continue;
    const auto a = state_at(r, from), b = state_at(r, to);
    if (!a || !b) continue;
    // A gesture the camera cannot see (the truth's expected mode is HOVER for most of it: the arm out of view,
    // e.g. the drone came close and high) asks nothing of the drone: said, not judged.
    if (!seg.seen) {
      std::fprintf(stderr, "not judged %s %5.1f-%5.1f s: out of the camera's view on most of its frames\n",
                   kGestureNames[gesture], (from - r.truth.front().t) * 1e-6, (to - r.truth.front().t) * 1e-6);
      continue;
    }
    // Frames of the judged stretch whose GESTURE_CMD is still the previous gesture's command.
    size_t old = 0, n = 0;
    const int old_mode = k > 0 ? segments[k - 1].mode : static_cast<int>(gesture_cmd_t::MODE_HOVER);
    for (size_t i = seg.begin; i < seg.end; ++i)
      if (truth[i].utime >= from) ++n, old += old_mode != seg.mode && commands[i].mode == old_mode;
    const double dn = b->n - a->n, de = b->e - a->e, dd = b->d - a->d;
    const auto& person = r.truth[seg.begin].m.person_position;
    const double range_a = std::hypot(person[0] - a->n, person[1] - a->e);
    const double range_b = std::hypot(person[0] - b->n, person[1] - b->e);
    char line[240];
    std::snprintf(line, sizeof line,
                  "%-7s %5.1f-%5.1f s: moved n %+.2f e %+.2f d %+.2f m, range %.2f -> %.2f m; old command on %zu of %zu frames",
                  kGestureNames[gesture], (from - r.truth.front().t) * 1e-6, (to - r.truth.front().t) * 1e-6,
                  dn, de, dd, range_a, range_b, old, n);
    std::fprintf(stderr, "judged %s\n", line);
    SCOPED_TRACE(line);
    if (std::find(open_findings.begin(), open_findings.end(), gesture) != open_findings.end()) {
      // How far it flew the way asked: up, down, in, out (OUT and REST have no one way: never open findings).
      double asked = 0;
      switch (gesture) {
        case ground_truth_t::GESTURE_UP: asked = -dd; break;
        case ground_truth_t::GESTURE_DOWN: asked = dd; break;
        case ground_truth_t::GESTURE_CLOSER: asked = range_a - range_b; break;
        case ground_truth_t::GESTURE_FURTHER: asked = range_b - range_a; break;
        default: ADD_FAILURE() << kGestureNames[gesture] << " cannot be an open finding: it has no one way to fly"; break;
      }
      EXPECT_GT(asked, -0.10) << "an open finding, but it flew the other way";
      std::fprintf(stderr, "  an open finding: %s; judged only for not flying the other way\n", asked > 0.10 ? "flown" : "not flown");
      ++j.checked;
      ++j.per_gesture[gesture];
      continue;
    }
    switch (gesture) {
      case ground_truth_t::GESTURE_OUT: {
        // The asked direction, frame by frame in the world (the drone yaws to keep facing the user as it goes),
        // as the user pointed kSettle earlier (within this gesture): a command follows the arm within that
        // reaction time, so an arm that keeps moving (fine piloting) is followed with that lag, by design.
        double want[3] = {0, 0, 0};
        size_t asked = seg.begin;
        for (size_t i = seg.begin; i < seg.end; ++i) {
          const auto& f = r.truth[i];
          if (f.t < from) continue;
          while (asked + 1 < i && r.truth[asked + 1].t <= f.t - kSettle) ++asked;
          const auto s = state_at(r, f.t);
          if (!s) break;
          double w[3];
          camera_to_world(r.truth[asked].m.expected_direction, s->yaw, w);
          for (int k = 0; k < 3; ++k) want[k] += w[k];
        }
        const double dot = want[0] * dn + want[1] * de + want[2] * dd;
        const double norms = std::hypot(want[0], want[1], want[2]) * std::hypot(dn, de, dd);
        EXPECT_GT(std::hypot(dn, de, dd), 0.10) << "did not fly where the user pointed";
        const double angle = std::acos(std::clamp(dot / norms, -1.0, 1.0)) * 180 / M_PI;
        EXPECT_LT(angle, 15.0) << "flew " << angle << "° off the pointed direction";
        break;
      }
      case ground_truth_t::GESTURE_UP: EXPECT_LT(dd, -0.05) << "did not climb"; break;
      case ground_truth_t::GESTURE_DOWN: EXPECT_GT(dd, 0.05) << "did not descend"; break;
      case ground_truth_t::GESTURE_CLOSER: EXPECT_LT(range_b - range_a, -0.10) << "did not close in"; break;
      case ground_truth_t::GESTURE_FURTHER: EXPECT_GT(range_b - range_a, 0.10) << "did not back off"; break;
      case ground_truth_t::GESTURE_REST: EXPECT_LT(std::hypot(dn, de, dd), rest_drift_m) << "drifted at rest"; break;
    }
    ++j.checked;
    ++j.per_gesture[gesture];
  }
  return j;
}

cv::Rect2d rect_of(const float* xywh) { return {xywh[0], xywh[1], xywh[2], xywh[3]}; }

// The track on the user: TRACKING, its box with IoU >= 0.5 with the user's true box.
bool on_user(const user_track_t& t, const ground_truth_t& m) {
  return t.status == user_track_t::STATUS_TRACKING && iou(rect_of(t.box), rect_of(m.user_box)) >= 0.5;
}

// The track against the truth (issues 13, 30): of the frames TRACKING with the user in view (true box centre in
// the image) or wholly out of it (nobody the drone should follow), the share whose box has IoU >= 0.5 with the
// user's true box (the drone flies after whoever is tracked). Frames with the user partly in view, centre out,
// are not judged.
double share_on_user(const Recorded& r) {
  int64_t tracking = 0, on = 0;
  for (const auto& f : r.truth) {
    const auto t = r.tracks.find(f.m.seq);
    if (t == r.tracks.end() || t->second.status != user_track_t::STATUS_TRACKING) continue;
    const float* b = f.m.user_box;
    const double w = t->second.image_width, h = t->second.image_height;
    const double cx = b[0] + 0.5 * b[2], cy = b[1] + 0.5 * b[3];
    const bool centre_in = b[2] > 0 && cx >= 0 && cy >= 0 && cx < w && cy < h;
    const bool wholly_out = !(b[2] > 0) || b[0] + b[2] <= 0 || b[0] >= w || b[1] + b[3] <= 0 || b[1] >= h;
    if (!centre_in && !wholly_out) continue;
    ++tracking;
    on += on_user(t->second, f.m);
  }
  return tracking ? static_cast<double>(on) / static_cast<double>(tracking) : 0.0;
}

// Re-acquisition (issue 30): each time the user is back fully in view (the true face inside the frame, the true
// body box within it side to side) after at least 1 s out of it or turned away (the truth has no face then), the
// seconds until the track is on them again (on_user; 0 when it held them); infinity when it never is.
std::vector<double> reacquire_delays_s(const Recorded& r) {
  constexpr int64_t kAwayUs = 1'000'000;
  std::vector<double> delays;
  constexpr int64_t kNone = -1;
  int64_t away_since = kNone, back_at = kNone;  // capture utime
  for (const auto& f : r.truth) {
    const auto t = r.tracks.find(f.m.seq);
    if (t == r.tracks.end()) continue;
    const float *b = f.m.user_box, *face = f.m.face_box;
    const double w = t->second.image_width, h = t->second.image_height;
    const bool in_view = b[2] > 0 && face[2] > 0 && face[0] >= 0 && face[1] >= 0 && face[0] + face[2] <= w &&
                         face[1] + face[3] <= h && b[0] >= 0 && b[0] + b[2] <= w;
    if (!in_view) {
      if (away_since == kNone) away_since = f.m.utime;
      continue;
    }
    if (away_since != kNone && f.m.utime - away_since >= kAwayUs && back_at == kNone) back_at = f.m.utime;
    away_since = kNone;
    if (back_at != kNone && on_user(t->second, f.m)) {
      delays.push_back(1e-6 * static_cast<double>(f.m.utime - back_at));
      back_at = kNone;
    }
  }
  if (back_at != kNone) delays.push_back(std::numeric_limits<double>::infinity());
  return delays;
}

// GESTURE_CMD's mode against the truth's expected mode on the frames with the drone 8 to 10 m from the user
// (horizontal), from 0.8 s after each change of the expected mode (gpilot-report's settling for the evidence
// rule): the paper's range. Returns {judged frames, share right}.
std::pair<int64_t, double> accuracy_at_8_to_10_m(const Recorded& r) {
  const auto settle_us = static_cast<int64_t>(ScoreRules{}.judged_after_s * 1e6);
  int64_t judged = 0, right = 0, change_utime = 0;
  int prev = -1;
  for (const auto& f : r.truth) {
    if (f.m.expected_mode != prev) change_utime = f.m.utime;
    prev = f.m.expected_mode;
    const double range = std::hypot(f.m.person_position[0] - f.m.camera_position[0], f.m.person_position[1] - f.m.camera_position[1]);
    const auto c = r.commands.find(f.m.seq);
    if (f.m.utime - change_utime < settle_us || range < 8.0 || range >= 10.0 || c == r.commands.end()) continue;
    ++judged;
    right += c->second.mode == f.m.expected_mode;
  }
  return {judged, judged ? static_cast<double>(right) / static_cast<double>(judged) : 0.0};
}

// max_false_at_rest and rest_drift_m: 0 and 0.10 m; a scenario that does not meet them yet says why it is
// allowed more (an open finding, issue 14), so that the rest of it still guards every run. min_on_user: the
// share of TRACKING frames on the user (share_on_user; 0: not judged); min_far_accuracy: decided right at
// 8-10 m (accuracy_at_8_to_10_m, at least 200 frames judged; 0: not judged).
struct Scenario {
  std::string name;
  double duration_s;
  std::vector<int> must_judge;
  int max_false_at_rest = 0;
  double rest_drift_m = 0.10;
  double min_on_user = 0.0;
  double min_far_accuracy = 0.0;
  std::string config = "synthetic";  //!< deploy/config/<config>.yaml
  bool video = false;                //!< gpilot-view writes the annotated MP4, and the test checks it
  std::string variant = "";          //!< appended to the test's name: the same scenario flown with another config
  std::vector<int> open_findings = {};  //!< gestures judged only for not flying the other way (judge_gestures)
  double max_moving_at_rest = 1.0;      //!< share of the scored frames flown with a motion while the user rests
  double max_reacquire_s = 0.0;         //!< the user tracked again within this of being back in view (0: not judged)
};

// Seconds of each run (from the log's start) whose hands stage is replayed and checked; the tour's in full.
constexpr int kHandsReplayS = 25;

class ScenarioE2E : public ::testing::TestWithParam<Scenario> {};

TEST_P(ScenarioE2E, TrajectoryDoesWhatTheGesturesAsk) {
  const Scenario& sc = GetParam();
  const std::string dir = fs::temp_directory_path() / ("gpilot-e2e-" + sc.name + (sc.variant.empty() ? "" : "-" + sc.variant) + "-" + std::to_string(getpid()));
  const char* given = std::getenv("GPILOT_E2E_LOG");
  const Recorded r = read_log(given ? std::string(given) : run_pipeline(sc.name, dir, sc.duration_s, "", nullptr, sc.config, sc.video));
  ASSERT_GT(r.states.size(), 100u);
  ASSERT_GT(r.truth.size(), 100u);
  const Judged j = judge_gestures(r, sc.rest_drift_m, sc.open_findings);
  for (int g : sc.must_judge) EXPECT_TRUE(j.per_gesture.count(g)) << "no " << kGestureNames[g] << " long enough to judge";
  const Score& d = j.decide;
  std::fprintf(stderr,
               "decide: %d changes, reaction median %.2f s (%d frames), max %.2f s (%d frames), missed %d; old command on "
               "%lld of %lld frames (%.1f %%), any other wrong command on %lld; false at rest %d (%lld frames), "
               "confused %d (%lld frames)\n",
               d.changes, d.reaction_median_s(), d.reaction_median_frames(), d.reaction_max_s(), d.reaction_max_frames(),
               d.missed, static_cast<long long>(d.old_frames), static_cast<long long>(d.frames),
               d.frames ? 100.0 * d.old_frames / d.frames : 0.0, static_cast<long long>(d.wrong_frames - d.old_frames),
               d.false_at_rest, static_cast<long long>(d.false_at_rest_frames), d.confused,
               static_cast<long long>(d.confused_frames));
  // What the drone flew: the recorded FLIGHT_SETPOINT's mode, frame by frame (the command spacing holds back a
  // command that comes within 0.3 s of the last one taken: a hand lowered slowly through the FURTHER zone after
  // CLOSER gave a 6-frame FURTHER GESTURE_CMD in a nuisances run, never flown).
  const std::string path = given ? std::string(given) : dir + "/log.lcmlog";
  const EvalLog recorded = read_eval_log(path);
  ASSERT_FALSE(recorded.recorded_flown.empty())
      << path << ": no FLIGHT_SETPOINT decodes (a log from code whose messages differ?): what was flown is unknown";
  const Score flown = score_commands(truth_of(recorded), recorded.recorded_flown, ScoreRules{});
  std::fprintf(stderr, "flown: reaction median %.2f s, max %.2f s; false at rest %d (%lld frames), confused %d (%lld frames)\n",
               flown.reaction_median_s(), flown.reaction_max_s(), flown.false_at_rest,
               static_cast<long long>(flown.false_at_rest_frames), flown.confused, static_cast<long long>(flown.confused_frames));
  EXPECT_LE(flown.false_at_rest, sc.max_false_at_rest) << "the drone was asked to move while the user rested";
  const double moving_at_rest = flown.frames ? static_cast<double>(flown.false_at_rest_frames) / flown.frames : 0.0;
  EXPECT_LE(moving_at_rest, sc.max_moving_at_rest) << "flown with a motion on too many frames while the user rested";
  const double on_user = share_on_user(r);
  const auto [far_judged, far_right] = accuracy_at_8_to_10_m(r);
  std::fprintf(stderr, "track on the user on %.1f %% of TRACKING frames; at 8-10 m %lld frames judged, %.1f %% right\n",
               100.0 * on_user, static_cast<long long>(far_judged), 100.0 * far_right);
  if (sc.min_on_user > 0) {
    EXPECT_GE(on_user, sc.min_on_user) << "the track left the user (a bystander?)";
  }
  if (sc.max_reacquire_s > 0) {
    const std::vector<double> delays = reacquire_delays_s(r);
    EXPECT_FALSE(delays.empty()) << "the user never left the view for 1 s: no re-acquisition to judge";
    for (const double d : delays) {
      std::fprintf(stderr, "the user back in view: tracked again after %.2f s\n", d);
      EXPECT_LE(d, sc.max_reacquire_s) << "the user was not tracked again in time";
    }
  }
  if (sc.min_far_accuracy > 0) {
    EXPECT_GE(far_judged, 200) << "too little flown at 8-10 m";
    EXPECT_GE(far_right, sc.min_far_accuracy) << "gestures at 8-10 m decided wrong";
  }
  if (!given) {
    // The live run replays: each stage's code over what it received, with the config it published on CONFIG,
    // gives exactly what it sent (as ./deploy/run checks after a flight). Flight too: its service with its
    // timer fired at the recorded setpoints' instants, from the first one (tools/replay/replay_ticks.hpp).
    // A log given with GPILOT_E2E_LOG may come from older code and is not replayed.
    // The hands stage on pose costs ~15 ms of CPU a frame to replay, a whole run 15-30 s beside the other test's
    // live pipeline: every run replays it over its first kHandsReplayS, the tour (every gesture, the video) in
    // full. Replay is exact from a log's start only (the pose track carries each frame's ROI to the next).
    for (const char* stage : {"tracker", "hands", "decide", "flight"}) {
      const std::string window =
          std::string(stage) == "hands" && !sc.video ? " --to " + std::to_string(kHandsReplayS) : std::string();
      const test::CommandOutput replay = test::run_command(std::string(GPILOT_BIN_DIR) + "/gpilot-replay " + path +
                                                           " --stage " + stage + window + " --check 2>/dev/null");
      EXPECT_EQ(replay.code, 0) << stage << "'s replay of the live run differs:\n" << replay.out;
      EXPECT_NE(replay.out.find("\n0 differences"), std::string::npos) << stage << ":\n" << replay.out;
    }
    if (sc.video) {
      EXPECT_GT(fs::file_size(dir + "/annotated.mp4"), 10'000u) << "no annotated video";
    }
    // A failed run is kept to look into; GPILOT_E2E_KEEP keeps every run (gpilot-report on its log).
    if (HasFailure() || std::getenv("GPILOT_E2E_KEEP")) std::fprintf(stderr, "run kept in %s\n", dir.c_str());
    else fs::remove_all(dir);
  }
}

using G = ground_truth_t;
INSTANTIATE_TEST_SUITE_P(
    Scenarios, ScenarioE2E,
    ::testing::Values(
        Scenario{"tour", 70, {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN, G::GESTURE_CLOSER, G::GESTURE_FURTHER},
                 0, 0.10, 0.0, 0.0, "synthetic", true},
        Scenario{"fine-piloting", 50, {G::GESTURE_REST, G::GESTURE_OUT}},
        Scenario{"closer-further", 45, {G::GESTURE_REST, G::GESTURE_CLOSER, G::GESTURE_FURTHER}},
        Scenario{"idle", 35, {G::GESTURE_REST}},
        // Issue 29, gesticulation is not a command: hands moving about in front of the body as in talking, no
        // gesture held. Without decide's hold (front_hold_frames 1) a live run flew 13 false commands on 32 % of
        // its frames; with it, 2-3 on 5.0-6.5 % in six runs and 10.6 % in one. The bar is 10 %: not met
        // in every run (an open finding): at 30.5-35 s the hand pauses 0.6 s, then visits places that differ mostly in
        // depth, within 0.04 m in the image, all above the body centre: a held CLOSER to the camera. Judged here
        // at 15 %; the drift is what that share flies (0.3 m/s), not judged apart.
        Scenario{"talking", 45, {G::GESTURE_REST}, 4, 2.0, 0.0, 0.0, "synthetic", false, "", {}, 0.15},
        // Open finding (issues 10, 14, the skin method): after UP the drone was high and close, the user's hips below
        // the frame (the flight stage now stops the climb before). The CLOSER flown for ~1 s at 40-42 s (a resting
        // hand at the bottom edge, "higher" than a body centre below the frame) is gone, and half the DOWN at
        // 52-54 s on a yellow wall at the bottom edge (hands.needs_body_centre). Left: that wall just above the
        // border, read as an OUT hand (DOWN, 53.6 s).
        // Open finding (issue 29, pose): under the 6 px motion blur BlazePose may read the resting arm raised beside
        // the UP arm (both arms 145-172 deg from down: no command, a run did not climb), and during CLOSER it may
        // place the resting arm, against the sandstone wall, bent between the hips (both arms in front: no
        // command, a run closed in 0.07 m). Judged here only for not flying the other way. DOWN likewise (issue
        // 29, pose, as bystander's): under light 1.4 BlazePose scores the DOWN arm's wrist 0.27-0.35 visible, in
        // plain view at 48-52 deg from down: no command, a fresh-clone run did not descend. Open finding (issue 29,
        // pose): since the flight stage holds the climb with the user box's bottom at the frame's bottom, CLOSER
        // comes with the hips in view (and is itself held there: flight.view_box_ratio). Seen from 1.9-2 m up, the
        // hand held high projects only 0.14 torso heights above p_bc (0.21-0.26 from 1.5-1.65 m, tour and
        // dark-skin), and under JPEG 25 BlazePose may place it 15-35 px low, below p_bc, on every frame of the
        // gesture (the figure holds still): FURTHER flew 0.30 m and 0.58 m in 2 of 17 runs (a failure here).
        Scenario{"nuisances", 70, {G::GESTURE_REST, G::GESTURE_OUT}, 2, 0.20, 0.0, 0.0, "synthetic", false, "",
                 {G::GESTURE_UP, G::GESTURE_CLOSER, G::GESTURE_DOWN}},
        // Issue 29: the UP arm flies faster than the DOWN arm (the speed follows the hand's reach), so the drone is
        // above its start by CLOSER. Before the flight stage held the climb with the user box's bottom at the
        // frame's bottom (flight.view_box_ratio) that was 2.3 m up at 3.3 m, the hips on the bottom edge,
        // BlazePose scoring the dark forearm across the chest 0.2-0.45: CLOSER and FURTHER were missed in 3 of 5
        // runs (an open finding). With the hold, both flown in 10 of 10 runs (CLOSER 0.64-1.10 m, FURTHER 1.09-1.18 m).
        Scenario{"dark-skin", 70, {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN, G::GESTURE_CLOSER, G::GESTURE_FURTHER},
                 0, 0.10},
        // Issue 13, the paper's range: from 5 m out to 8-10 m with FURTHER, every gesture there (>= 90 % right).
        // Issue 29, pose: with MediaPipe's smoothing of the auxiliary points the crop lagged the UP arm at 9.7 m,
        // the model read it folded for the whole gesture and UP was not flown (1 of 10 runs; 3 of 16 before);
        // with their beta 5 the crop follows (services/pose/README.md).
        Scenario{"far", 76, {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN, G::GESTURE_CLOSER, G::GESTURE_FURTHER}, 0, 0.10, 0.95, 0.90},
        // Issue 13, the user, not a bystander: the track stays on the user through a look-alike walker crossing in
        // front and beside a waver. Open finding (hands, issue 13): the waver's raised hand inside the user's
        // search rectangle reached GESTURE_CMD as FINE in a few short episodes while the user rested. Issue 29:
        // after UP (0.5 m climbed) the user stood at the frame's bottom, legs cut, and BlazePose could score the DOWN
        // arm's wrist 0.32, in plain view (a run did not descend: an open finding); since the flight stage stops
        // climbing with the user box's bottom at the frame's bottom, DOWN flew 0.41-0.46 m in 8 of 8 runs.
        Scenario{"bystander", 72, {G::GESTURE_REST, G::GESTURE_OUT}, 4, 0.10, 0.95},
        // Issue 30, the user found by the body alone: 9 m away from the start, the cascade as shot (no face below
        // 20 px), the person search on (synthetic-body.yaml); every gesture there (>= 90 % right at 8-10 m).
        Scenario{"far-no-face", 50, {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN, G::GESTURE_CLOSER, G::GESTURE_FURTHER}, 0, 0.10, 0.95, 0.90, "synthetic-body"},
        // Issue 30, re-acquisition: the user walks out of the frame and back in 4 s later, a look-alike walker in
        // other clothes crossing meanwhile: tracked again within 1 s of being back in view, the walker never. The
        // drone holds its heading (synthetic-fixed-heading.yaml): with the default it turns after the user.
        Scenario{"walk-out", 35, {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN}, 0, 0.10, 0.95, 0.0,
                 "synthetic-fixed-heading", false, "", {}, 1.0, 1.0},
        // Issue 30, the back turned: the user turns away for 3 s, an arm out meanwhile (no command with the back
        // turned), and faces the drone again: tracked within 1 s of facing it, the gestures after it flown.
        Scenario{"turn-around", 36, {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN}, 0, 0.10, 0.95, 0.0,
                 "synthetic", false, "", {}, 1.0, 1.0},
        // The paper's skin method (hands.method skin), every gesture. Open finding (skin): its body centre p_bc is
        // the user box's centre, the hips; after CLOSER (the drone 2.4 m off and above the user) the hand held low
        // in front projects onto that line (hand y 305 px, p_bc 304, the truth's torso centre 283: the tracker's
        // box is the true one within 10 px) and reads as "higher" or within decide's dead zone: FURTHER was not
        // flown in 4 of 6 runs on this machine, with decide's hold and with the code before it. Judged only for
        // not flying the other way.
        Scenario{"tour", 70, {G::GESTURE_REST, G::GESTURE_OUT, G::GESTURE_UP, G::GESTURE_DOWN, G::GESTURE_CLOSER, G::GESTURE_FURTHER},
                 0, 0.10, 0.0, 0.0, "synthetic-skin", false, "skin", {G::GESTURE_FURTHER}}),
    [](const auto& info) {
      std::string n = info.param.name + (info.param.variant.empty() ? "" : "_" + info.param.variant);
      std::replace(n.begin(), n.end(), '-', '_');
      return n;
    });

class KillE2E : public ::testing::TestWithParam<std::string> {};

TEST_P(KillE2E, StageKilledMidFlightGivesZeroSetpointAndIsRestarted) {
  const std::string stage = GetParam();
  const std::string dir = fs::temp_directory_path() / ("gpilot-e2e-kill-" + stage + "-" + std::to_string(getpid()));
  int64_t killed_at = 0;
  // Killed while the user points sideways (from 4 s into the tour) and the drone flies that way.
  const Recorded r = read_log(run_pipeline("tour", dir, 22, stage, &killed_at));
  ASSERT_GT(killed_at, 0);
  const auto& pids = r.health_pids.at(stage);
  const int32_t first = pids.front().second;
  int64_t restart_t = 0;
  for (const auto& [t, pid] : pids)
    if (pid != first) { restart_t = t; break; }
  EXPECT_GT(restart_t, killed_at) << "no HEALTH from a restarted " << stage;

  double before = 0;  // the fastest setpoint in the second before the kill: it was flying
  std::optional<double> after;  // the first setpoint from 0.3 s after the kill
  bool resumed = false;
  for (const auto& sp : r.setpoints) {
    if (sp.t > killed_at - 1'000'000 && sp.t < killed_at) before = std::max(before, sp.speed);
    if (sp.t >= killed_at + 300'000 && !after) after = sp.speed;
    if (restart_t > 0 && sp.t > restart_t && sp.speed > 0) resumed = true;
  }
  EXPECT_GT(before, 0.05) << "the drone was not flying when " << stage << " was killed: the test proves nothing";
  ASSERT_TRUE(after.has_value()) << "no setpoint after the kill";
  EXPECT_EQ(*after, 0.0) << "still moving 0.3 s after " << stage << " died";
  EXPECT_TRUE(resumed) << "control did not resume after " << stage << " came back";
  if (HasFailure()) std::fprintf(stderr, "run kept in %s\n", dir.c_str());
  else fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Stages, KillE2E,
                         ::testing::Values("gpilot-capture", "gpilot-tracker", "gpilot-hands", "gpilot-decide",
                                           "gpilot-flight"),
                         [](const auto& info) { return info.param.substr(7); });

}  // namespace
}  // namespace gpilot
