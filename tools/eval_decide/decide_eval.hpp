// gpilot-eval-decide's core: the decide stage (GestureDecider, the service's own classes) and the flight
// stage's command adoption (FlightBridge) run over a log's HAND_OBS, scored against its GROUND_TRUTH: how long
// after a true gesture change the new command comes, how many frames still carry the old one, and how often
// a command nobody asked for is given. No bus, no clock: time is the frames' utime.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "decide/decide_params.hpp"
#include "decide/gesture_decider.hpp"
#include "flight/flight_params.hpp"
#include "flight/flight_types.hpp"

namespace gpilot {

// One HAND_OBS frame with the ground truth of the same seq.
struct EvalFrame {
  HandObservation obs;
  UserTrack track;           //!< what the flight stage knows of the user in this frame (from HAND_OBS)
  int gesture = 0;           //!< ground_truth_t::GESTURE_*: what the user means
  int expected_mode = 0;     //!< gesture_cmd_t::MODE_* the paper's rules give on the true hand positions
  double expected_dir[2] = {0.0, 0.0};  //!< the truth's camera-frame x, y (box widths)
};

// A command as the scoring sees it: a mode and, for FINE/UP/DOWN, the camera-frame x, y.
struct ScoredCommand {
  int mode = 0;
  double dir[2] = {0.0, 0.0};
};

struct EvalLog {
  std::string path;
  std::vector<EvalFrame> frames;  //!< HAND_OBS in log order, each with its GROUND_TRUTH
  int64_t hand_obs_without_truth = 0;
  // What a live run (./deploy/run, the e2e test) recorded, one per frame, when the log has it: the GESTURE_CMD of
  // the frame's seq, and what FLIGHT_SETPOINT flew when the next frame's GROUND_TRUTH was logged (its mode;
  // FINE's direction from the GESTURE_CMD it follows).
  std::vector<ScoredCommand> recorded_cmd, recorded_flown;
};

// Reads HAND_OBS and GROUND_TRUTH (joined by seq); throws LogError for an unreadable log, std::runtime_error
// for one without both channels.
EvalLog read_eval_log(const std::string& path);

// How the truth is cut into gestures and what counts as the right command.
struct ScoreRules {
  double turn_deg = 30.0;       //!< an OUT gesture whose pointed direction turns more than this is a new gesture
  double fine_angle_deg = 30.0; //!< a FINE command within this angle of the truth's direction is the right one
  double min_turn_s = 1.0;      //!< a turned piece of an OUT gesture shorter than this is the arm on its way to the
                                //!< next piece: one gesture with it (its change is the true gesture's change)
  double judged_after_s = 0.8;  //!< a run is judged frame by frame from this long after each true change (the
                                //!< reaction bar, issue 14: median <= 0.5 s, max <= 0.8 s)
};

// The truth of one frame, as the scoring needs it.
struct TruthFrame {
  int64_t utime = 0;
  int gesture = 0;
  int expected_mode = 0;
  double dir[2] = {0.0, 0.0};
};

// One true gesture: frames [begin, end), the command it asks for (HOVER at REST; else the most frequent
// expected mode of its frames), and whether the camera saw it (not: most frames' expected mode is HOVER
// although the user gestures; such a gesture is not scored).
struct TruthSegment {
  size_t begin = 0, end = 0;
  int mode = 0;
  double dir[2] = {0.0, 0.0};  //!< mean truth direction over its FINE frames
  bool seen = true;
};
std::vector<TruthSegment> truth_segments(const std::vector<TruthFrame>& truth, const ScoreRules& rules);

struct Score {
  int64_t frames = 0;          //!< scored frames (frames of seen gestures)
  double minutes = 0.0;        //!< duration of the scored frames
  int changes = 0;             //!< true gesture changes scored (every seen gesture after the first)
  int missed = 0;              //!< changes whose new command never came before the next change
  std::vector<int64_t> reaction_us;  //!< per change that got its command: change -> first right command
  std::vector<int> reaction_frames;
  struct Change { int64_t utime; int from_mode, to_mode; int frames; };  //!< frames -1: missed
  std::vector<Change> change_list;   //!< every scored change, in order (--changes)
  std::vector<Change> false_list;    //!< every false or confused episode: truth's mode, commanded mode, frames
  int64_t old_frames = 0;      //!< frames from each change up to its first right command (the reaction)
  int64_t wrong_frames = 0;    //!< frames whose command is not the one the truth asks for (old ones included)
  // A command nobody asked for: not HOVER, not the truth's, not the previous gesture's command still held
  // while the reaction runs, and not the one the paper's rules give on the frame's true hands (the next
  // gesture's shown early, or one the arm passes through on its way). Counted in episodes
  // (onsets) and frames.
  int false_at_rest = 0;       //!< ... while the user rests
  int64_t false_at_rest_frames = 0;
  int confused = 0;            //!< ... while the user asks for another motion (CLOSER for FURTHER, UP for FINE)
  int64_t confused_frames = 0;

  void add(const Score& o);    //!< pools another log's score into this one
  double reaction_median_s() const;
  double reaction_max_s() const;
  int reaction_median_frames() const;
  int reaction_max_frames() const;
  double false_per_minute() const { return minutes > 0 ? (false_at_rest + confused) / minutes : 0.0; }
};

// Scores one command per truth frame (commands.size() == truth.size()).
Score score_commands(const std::vector<TruthFrame>& truth, const std::vector<ScoredCommand>& commands,
                     const ScoreRules& rules);

// The decide stage's commands over a log (one per frame), and what the flight stage flies at each frame's
// time given those commands (FlightBridge with the operator engaged; its command spacing is what differs).
struct StageRun {
  std::vector<ScoredCommand> decided;
  std::vector<ScoredCommand> flown;
};
StageRun run_stages(const EvalLog& log, const DecideParams& decide, const FlightParams& flight);

std::vector<TruthFrame> truth_of(const EvalLog& log);

}  // namespace gpilot
