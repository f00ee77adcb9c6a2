// What gpilot-report measures in a run's log: frames, commands per mode, per-stage rates and processing
// times (HEALTH), end-to-end latency (frame utime to the receipt of its GESTURE_CMD / first
// FLIGHT_SETPOINT, matched by seq), gesture accuracy against GROUND_TRUTH with a confusion matrix, and the
// vehicle's path coloured by the gesture mode in force. Pure: messages and their log receipt times in,
// numbers out; no LCM, no clock, no files.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "decide_eval.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"
#include "json_out.hpp"

namespace gpilot {

constexpr int kModes = 6;  // gesture_cmd_t.MODE_HOVER .. MODE_FURTHER

struct LatencyStats {
  int64_t n = 0;
  double median_ms = 0;  // nearest-rank; meaningful only when n > 0
  double p95_ms = 0;
};

struct StageHealth {
  std::string name;
  int64_t reports = 0;
  double rate_out_last_hz = 0;
  double rate_out_median_hz = 0;     // over reports after the first (the first has no period)
  double processing_p50_ms = 0;      // median over reports of the period's p50 (periods with samples)
  double processing_p99_ms = 0;      // median over reports of the period's p99
  double processing_p99_max_ms = 0;  // worst period
  int64_t messages_in = 0, messages_out = 0, rejected = 0, dropped = 0;  // last report
  // CPU (HEALTH.cpu_s) used between a process's first and last report (summed over restarts), per CAMERA frame
  // received in those windows and as a share of one core; -1 when the reports carry none (one report, no frames).
  double cpu_ms_per_frame = -1;
  double cpu_percent = -1;
  int last_state = 0;
  std::string last_reject_reason;
};

// Which frames after a change of the expected gesture the accuracy leaves out: the paper's rule cannot decide
// before its buffer is past the threshold (buffer_size / 2 + 1 frames); the evidence rule is judged from
// ScoreRules::judged_after_s (0.8 s) on, as the e2e tests judge the flight.
struct Settling {
  int frames = 0;       // frames left out after each change (the paper's rule), or
  double seconds = 0;   // the time left out after each change (by GROUND_TRUTH utime)
  std::string why;      // in words, for the JSON
};
// decide.rule paper: buffer_size / 2 + 1 frames; else ScoreRules{}.judged_after_s.
Settling settling_for(const std::string& rule, int buffer_size);

struct Accuracy {
  int settle_frames = 0;   // frames skipped after each change of expected_mode (the paper's rule), or
  double settle_s = 0;     // seconds skipped after each change (the evidence rule)
  std::string rule;        // the rule in words, for the JSON
  int64_t truth_frames = 0;         // GROUND_TRUTH messages
  int64_t frames_with_command = 0;  // of those, with a GESTURE_CMD of the same seq
  int64_t skipped_settling = 0;     // of those, inside a settling window
  int64_t evaluated = 0;
  int64_t correct = 0;
  bool has_value() const { return evaluated > 0; }
  double value() const { return evaluated > 0 ? static_cast<double>(correct) / evaluated : 0.0; }
  std::array<std::array<int64_t, kModes>, kModes> confusion{};  // [expected][decided]
};

// Messages of one channel that are not in the log, from the gaps in seq of each publisher's stream (a seq
// that goes back starts a new stream: a restarted process). On a counter channel (CAMERA, GROUND_TRUTH,
// VEHICLE_STATE, HEALTH per process) every seq is one message sent, so a gap is a message the logger lost;
// on a frame channel (USER_TRACK, HAND_OBS, GESTURE_CMD: the seq of the frame) a gap is a frame the stage
// or one before it skipped (their HEALTH.dropped) or a message the logger lost.
struct ChannelGaps {
  bool counter = false;   // a gap is a logger loss
  int64_t messages = 0;   // in the log
  int64_t missing = 0;    // seq values skipped inside streams
  int64_t streams = 0;    // publishers or restarts seen
};

// The track against the truth (issue 13): USER_TRACK's box against GROUND_TRUTH.user_box of the same seq, on
// every frame where both exist and the user is in view (the true box's centre inside USER_TRACK's image; a
// user behind or beside the camera is not). A box on the user has IoU >= 0.5;
// one TRACKING with IoU < 0.2 follows something else (a bystander, the background).
struct TrackVsTruth {
  int64_t frames = 0;     // frames with both a USER_TRACK and a true box
  int64_t tracking = 0;   // of those, TRACKING
  int64_t on_user = 0;    // TRACKING with IoU >= 0.5
  int64_t elsewhere = 0;  // TRACKING with IoU < 0.2
  double iou_sum = 0;     // over the TRACKING frames
  double iou_min = 1;     // over the TRACKING frames
  double mean_iou() const { return tracking ? iou_sum / static_cast<double>(tracking) : 0.0; }
  void add(int status, double iou);
};

// Gesture accuracy and the track per band of the drone's horizontal range to the user (GROUND_TRUTH's
// camera_position to person_position): the paper flies the user from 5 m out to about 10 m.
struct RangeBand {
  double from_m = 0, to_m = 0;  // [from, to); to = infinity for the last band
  int64_t truth_frames = 0;
  int64_t evaluated = 0, correct = 0;  // as Accuracy (the same settling rule)
  TrackVsTruth track;
};

// Whether the operator's ENGAGE took: from FLIGHT_SETPOINT's engaged flag, and gpilot-flight's HEALTH for why not
// (an ENGAGE refused by the autopilot's answer or its silence, a lost link).
struct Engagement {
  int64_t setpoints = 0, engaged_setpoints = 0;
  bool engaged_at_end = false;
  int64_t disengagements = 0;  // engaged setpoints followed by a not engaged one
  std::string last_refusal;    // gpilot-flight's last "refusing to engage: ..." or "disengaged: ...", "" if none
};

struct Summary {
  int64_t frames = 0;
  double duration_s = 0;  // first to last CAMERA utime
  double camera_hz = 0;   // (frames - 1) / duration
  std::array<int64_t, kModes> commands_by_mode{};
  int64_t commands = 0;
  int64_t track_frames = 0;                       // USER_TRACK messages
  std::array<int64_t, 3> track_by_status{};       // SEARCHING, TRACKING, LOST
  int64_t track_turned_away = 0;                  // TRACKING with the user turned away (no command read)
  std::vector<StageHealth> stages;                // by name
  LatencyStats latency_cmd, latency_setpoint;     // receipt - frame utime
  LatencyStats pipeline_cmd, pipeline_setpoint;   // receipt - CAMERA receipt (both on the logger's clock)
  int64_t unmatched_commands = 0;                 // GESTURE_CMD whose CAMERA frame is not in the log
  Accuracy accuracy;
  TrackVsTruth track_vs_truth;
  std::vector<RangeBand> range_bands;  // kRangeBandEdges
  // Every frame counted (no settling skipped): gpilot-eval-decide's scoring of the recorded GESTURE_CMD against
  // GROUND_TRUTH (reaction to each true change, frames still carrying the old command, false commands).
  Score reaction;
  int64_t vehicle_states = 0;
  double path_length_m = 0;
  Engagement engagement;
  std::map<std::string, ChannelGaps> gaps;  // by channel
  int64_t logger_lost() const;              // missing on counter channels: messages the logger lost
};

// The vehicle's path for the plot: one point per VEHICLE_STATE.
struct TrajectoryPoint {
  double t_s;                // since the first VEHICLE_STATE, by log receipt time
  double north, east, down;  // metres, NED
  double yaw;                // rad
  int mode;                  // GESTURE_CMD mode in force (the latest received before it), -1 before any
  bool has_person;
  double person_north, person_east;  // the latest GROUND_TRUTH person_position, when has_person
};

// The band edges of Summary::range_bands, metres: [0, 3) [3, 5) [5, 8) [8, 10) [10, inf).
inline const std::vector<double> kRangeBandEdges = {0.0, 3.0, 5.0, 8.0, 10.0};

class RunAnalyzer {
 public:
  // settling: what the accuracy leaves out after each change of the expected gesture (settling_for).
  explicit RunAnalyzer(Settling settling);

  // Each message with the time the logger received it; call in log order.
  void on_camera(const image_t& m, int64_t recv_utime);
  void on_track(const user_track_t& m, int64_t recv_utime);
  void on_command(const gesture_cmd_t& m, int64_t recv_utime);
  void on_setpoint(const flight_setpoint_t& m, int64_t recv_utime);
  void on_vehicle(const vehicle_state_t& m, int64_t recv_utime);
  void on_truth(const ground_truth_t& m, int64_t recv_utime);
  void on_health(const health_t& m, int64_t recv_utime);
  void on_hands(const hand_obs_t& m, int64_t recv_utime);  // counted for the gaps only

  Summary summary() const;
  const std::vector<TrajectoryPoint>& trajectory() const { return path_; }

 private:
  struct FrameTimes {
    int64_t utime = 0, recv = 0;
  };
  Settling settling_;
  int64_t frames_ = 0, first_frame_utime_ = 0, last_frame_utime_ = 0;
  std::map<int64_t, FrameTimes> frames_by_seq_;
  std::map<int64_t, int> command_mode_by_seq_;
  std::map<int64_t, TruthFrame> truth_by_seq_;
  struct TruthBox {
    std::array<float, 4> box{};
    double range_m = 0;
  };
  struct TrackBox {
    int status = 0;
    std::array<float, 4> box{};
    int width = 0, height = 0;  // of the image tracked
  };
  std::map<int64_t, TruthBox> truth_box_by_seq_;
  std::map<int64_t, TrackBox> track_box_by_seq_;
  std::map<int64_t, ScoredCommand> command_by_seq_;
  std::array<int64_t, kModes> commands_by_mode_{};
  int64_t commands_ = 0, unmatched_ = 0;
  std::array<int64_t, 3> track_by_status_{};
  int64_t track_turned_away_ = 0;
  int64_t track_frames_ = 0;
  std::vector<int64_t> lat_cmd_, lat_sp_, pipe_cmd_, pipe_sp_;
  std::map<int64_t, bool> setpoint_seen_;
  Engagement engagement_;
  std::map<std::string, std::vector<health_t>> health_;
  std::vector<TrajectoryPoint> path_;
  int current_mode_ = -1;
  bool has_person_ = false;
  double person_n_ = 0, person_e_ = 0;
  int64_t first_vehicle_recv_ = -1;
  // Gaps: the last seq of each (channel, publisher) stream.
  void note_seq(const std::string& channel, bool counter, const std::string& publisher, int64_t seq);
  std::map<std::string, ChannelGaps> gaps_;
  std::map<std::pair<std::string, std::string>, int64_t> last_seq_;
};

// One JSON object (common/json_out.hpp); `extra`'s members come first at the top level (log file, warnings ...).
json summary_json(const Summary& s, const json& extra = json::object());
// The human table.
std::string summary_table(const Summary& s);

}  // namespace gpilot
