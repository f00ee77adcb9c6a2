// gpilot-replay: runs one stage (or a chain) over an LCM log, faster than real time, through the very code
// the service runs (the stage's start_*_service on a BusNode over memq://), and writes a new log with the
// original inputs and the new outputs. --check compares the new outputs with the recorded ones. A stage is
// given the frames the live stage processed, not those it skipped falling behind (ReplayPacing), and the
// config the live stage published on CONFIG (unless --config or --set say otherwise). A timer-driven stage
// (flight) has its timer fired at the instants the live one's fired, with the inputs it had then
// (ReplayTicks), on the log's clock. A stage that pairs two inputs by seq gets each pair as the live one
// worked it, whatever order the log heard them in (PairHold); a TRACKER_INIT (a manual box, a reset) before the
// frame the live tracker acted on it (InitAlign).
// This is how a bug seen in the field is reproduced on a desk.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "decide/decide_channels.hpp"
#include "decide/decide_service.hpp"
#include "flight/flight_channels.hpp"
#include "flight/flight_service.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "init_align.hpp"
#include "pair_hold.hpp"
#include "replay_pacing.hpp"
#include "replay_ticks.hpp"
#include "hands/hands_channels.hpp"
#include "hands/hands_service.hpp"
#include "config_schema.hpp"
#include "log.hpp"
#include "process_channels.hpp"
#include "service_cli.hpp"
#include "system/opencv_threads.hpp"
#include "tracker/tracker_channels.hpp"
#include "tracker/tracker_service.hpp"

namespace gpilot {
namespace {

// Every gpilot message starts with the 8-byte type fingerprint, then utime and seq (big-endian int64).
int64_t int64_at(const std::vector<uint8_t>& d, size_t at) {
  if (d.size() < at + 8) return -1;
  int64_t v = 0;
  for (size_t i = at; i < at + 8; ++i) v = (v << 8) | d[i];
  return v;
}
int64_t utime_of(const std::vector<uint8_t>& d) { return int64_at(d, 8); }
int64_t seq_of(const std::vector<uint8_t>& d) { return int64_at(d, 16); }
int64_t seq_of_event(const lcm::LogEvent& ev) {
  const auto* p = static_cast<const uint8_t*>(ev.data);
  return seq_of(std::vector<uint8_t>(p, p + std::min<int32_t>(ev.datalen, 24)));
}

// A TRACKER_INIT the replay aligns (InitAlign): a manual box or a reset, decoded.
std::optional<tracker_init_t> aligned_init(const lcm::LogEvent& ev) {
  tracker_init_t m{};
  if (m.decode(ev.data, 0, ev.datalen) <= 0) return std::nullopt;
  if (m.command != tracker_init_t::COMMAND_SET_BOX && m.command != tracker_init_t::COMMAND_RESET) return std::nullopt;
  return m;
}

// The replay's outputs against the recorded ones, message by message, paired by (utime, seq): one output the
// logger lost (or one the replay did not give) is one difference, not a shift of every message after it.
// With a key twice on either side (no stage sends that), by position.
struct OutputComparison {
  int differing = 0, only_new = 0, only_recorded = 0;
  std::vector<int64_t> first_seqs;  // of the first differences
};
OutputComparison compare_outputs(const std::vector<std::vector<uint8_t>>& replayed,
                                 const std::vector<std::vector<uint8_t>>& recorded) {
  OutputComparison c;
  const auto note = [&](const std::vector<uint8_t>& m) {
    if (c.first_seqs.size() < 5) c.first_seqs.push_back(seq_of(m));
  };
  using Key = std::pair<int64_t, int64_t>;
  std::map<Key, const std::vector<uint8_t>*> by_key;
  bool unique = true;
  for (const auto& m : recorded) unique = by_key.emplace(Key{utime_of(m), seq_of(m)}, &m).second && unique;
  std::set<Key> seen;
  for (const auto& m : replayed) unique = seen.insert(Key{utime_of(m), seq_of(m)}).second && unique;
  if (!unique) {
    for (size_t i = 0; i < std::min(replayed.size(), recorded.size()); ++i)
      if (replayed[i] != recorded[i]) {
        ++c.differing;
        note(recorded[i]);
      }
    (replayed.size() > recorded.size() ? c.only_new : c.only_recorded) +=
        static_cast<int>(std::max(replayed.size(), recorded.size()) - std::min(replayed.size(), recorded.size()));
    return c;
  }
  for (const auto& m : replayed) {
    const auto it = by_key.find(Key{utime_of(m), seq_of(m)});
    if (it == by_key.end()) {
      ++c.only_new;
      note(m);
      continue;
    }
    if (*it->second != m) {
      ++c.differing;
      note(m);
    }
    by_key.erase(it);
  }
  for (const auto& [key, m] : by_key) {
    ++c.only_recorded;
    note(*m);
  }
  return c;
}

// gpilot-flight over a log: the same service, its vehicle states and what the autopilot said from the log
// (VehicleSource::FromBus: the vehicle is not simulated or flown again, the bridge's, the engage gate's and the
// link watch's decisions are replayed), its setpoint timer fired at each recorded FLIGHT_SETPOINT's utime with
// the command and track that setpoint names (ReplayTicks).
std::shared_ptr<void> start_flight_replayed(const Config& config, BusNode& node) {
  return start_flight_service(config, node, VehicleSource::FromBus);
}

ReplayTicks flight_ticks() {
  using namespace flight_channels;
  return ReplayTicks(
      kFlightSetpoint.name,
      [](const std::vector<uint8_t>& d, int64_t* utime, std::map<std::string, int64_t>* keys) {
        flight_setpoint_t m{};
        if (!decode_exactly(d.data(), d.size(), m).empty()) return false;
        *utime = m.utime;
        (*keys)[kGestureCmd.name] = m.latest_command_seq;
        (*keys)[kUserTrack.name] = m.track_utime;
        (*keys)[kFlightControl.name] = m.control_utime;
        return true;
      },
      {{kGestureCmd.name, seq_of}, {kUserTrack.name, utime_of}, {kFlightControl.name, utime_of}},
      {{kGestureCmd.name, -1}, {kUserTrack.name, 0}, {kFlightControl.name, 0}});
}

// The names a stage declares with this role (services/<stage>/<stage>_channels.hpp), but those in `except`.
template <size_t N>
std::vector<std::string> declared(const ChannelUse (&uses)[N], ChannelRole role, const std::set<std::string>& except = {}) {
  std::vector<std::string> names;
  for (const auto& u : uses)
    if (u.role == role && !except.count(u.name)) names.emplace_back(u.name);
  return names;
}

struct StageEntry {
  std::function<std::shared_ptr<void>(const Config&, BusNode&)> start;
  std::vector<std::string> inputs, outputs;
  std::vector<std::pair<std::string, std::string>> paced = {};  //!< (input, output): see ReplayPacing
  std::function<ReplayTicks()> ticks = nullptr;                  //!< a timer-driven stage: see ReplayTicks
  std::pair<std::string, std::string> paired = {};               //!< inputs given in pairs of one seq: see PairHold
};

const std::map<std::string, StageEntry>& stages() {
  using R = ChannelRole;
  namespace tc = tracker_channels;
  namespace hc = hands_channels;
  namespace dc = decide_channels;
  namespace fc = flight_channels;
  static const std::map<std::string, StageEntry> table = {
      {"tracker", {static_cast<std::shared_ptr<void> (*)(const Config&, BusNode&)>(start_tracker_service), declared(tc::kUses, R::In), declared(tc::kUses, R::Out),
                   {{tc::kCamera.name, tc::kUserTrack.name}}}},
      {"hands", {static_cast<std::shared_ptr<void> (*)(const Config&, BusNode&)>(start_hands_service), declared(hc::kUses, R::In), declared(hc::kUses, R::Out),
                 {{hc::kCamera.name, hc::kHandObs.name}}, nullptr, {hc::kCamera.name, hc::kUserTrack.name}}},
      {"decide", {start_decide_service, declared(dc::kUses, R::In), declared(dc::kUses, R::Out)}},
      // The vehicle and the autopilot are the log's: VEHICLE_STATE and AUTOPILOT are inputs here, not outputs.
      {"flight", {start_flight_replayed, declared(fc::kUses, R::In),
                  declared(fc::kUses, R::Out, {fc::kVehicleState.name, fc::kAutopilot.name}), {}, flight_ticks}},
  };
  return table;
}

// What gpilot-replay was asked (its command line).
struct ReplayOptions {
  std::string in_path, out_path, stage_arg;
  bool check = false, inputs_only = false, all_frames = false, recorded_outputs = false;
  double from_s = 0, to_s = 0;
};

// The stages of `--stage a,b,c`, checked: known, and a timer-driven stage alone (it is given its inputs in the
// order the live one had them, which only the log knows).
std::vector<std::string> parse_chain(const std::string& stage_arg) {
  std::vector<std::string> chain;
  std::stringstream ss(stage_arg);
  for (std::string s; std::getline(ss, s, ',');) {
    if (!stages().count(s)) throw std::invalid_argument("unknown stage '" + s + "' (tracker, hands, decide, flight)");
    chain.push_back(s);
  }
  for (const auto& s : chain)
    if (stages().at(s).ticks && chain.size() > 1)
      throw std::invalid_argument("stage '" + s + "' replays alone (its inputs come from the log, in the order it had them)");
  return chain;
}

// What the first pass over the log finds: the frames the live stages processed (ReplayPacing: their outputs'
// seqs), the config each live stage published on CONFIG when it started (the first one of its process name),
// and where a replayed tracker is given the log's manual boxes and resets (InitAlign: before the frame the live
// one acted on each).
struct LogScan {
  ReplayPacing pacing;
  std::map<std::string, std::string> logged_yaml;  // process -> YAML
  bool align_inits = false;
  InitAlign align;
  struct LoggedInit {
    int64_t timestamp;  // when the recorder heard it: the replay judges it there (bus.time_window_s)
    std::vector<uint8_t> bytes;
  };
  std::vector<LoggedInit> inits_logged;  // every aligned init, in log order
};

LogScan scan_log(const ReplayOptions& o, const std::vector<std::string>& chain, const std::set<std::string>& inputs,
                 bool read_configs) {
  namespace tc = tracker_channels;
  LogScan scan;
  if (!o.all_frames)
    for (const auto& s : chain)
      for (const auto& [input, output] : stages().at(s).paced) scan.pacing.add_rule(input, output);
  scan.align_inits = std::find(chain.begin(), chain.end(), "tracker") != chain.end() &&
                     inputs.count(tc::kTrackerInit.name) && inputs.count(tc::kCamera.name);
  const std::set<std::string> paced_outputs = scan.pacing.output_channels();
  lcm::LogFile log(o.in_path, "r");
  if (!log.good()) throw std::runtime_error(o.in_path + ": cannot open log");
  int32_t last_track_id = -1;
  int8_t last_status = -1;
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev; ev = log.readNextEvent()) {
    if (scan.align_inits) {
      if (ev->channel == tc::kCamera.name) {
        scan.align.frame(seq_of_event(*ev));
      } else if (ev->channel == tc::kUserTrack.name) {
        user_track_t t{};
        if (t.decode(ev->data, 0, ev->datalen) > 0) {
          const bool new_track = t.track_id != last_track_id;
          if (t.init_source == user_track_t::INIT_MANUAL && new_track)
            scan.align.manual_start(t.seq, {t.box[0], t.box[1], t.box[2], t.box[3]});
          else if (last_status == user_track_t::STATUS_TRACKING && (t.status != user_track_t::STATUS_TRACKING || new_track))
            scan.align.dropped(t.seq);
          last_track_id = t.track_id;
          last_status = t.status;
        }
      } else if (ev->channel == tc::kTrackerInit.name) {
        if (const auto m = aligned_init(*ev)) {
          if (m->command == tracker_init_t::COMMAND_SET_BOX) scan.align.set_box({m->box[0], m->box[1], m->box[2], m->box[3]});
          else scan.align.reset();
          const auto* p = static_cast<const uint8_t*>(ev->data);
          scan.inits_logged.push_back({ev->timestamp, std::vector<uint8_t>(p, p + ev->datalen)});
        }
      }
    }
    if (paced_outputs.count(ev->channel)) {
      scan.pacing.recorded(ev->channel, seq_of_event(*ev));
    } else if (read_configs && ev->channel == process_channels::kConfig.name) {
      config_t c{};
      if (c.decode(ev->data, 0, ev->datalen) > 0 && check_message(c).empty()) scan.logged_yaml.emplace(c.process, c.yaml);
    }
  }
  if (scan.align_inits) scan.align.finish();
  return scan;
}

// Each stage's config: the one its live process published in the log, else `given` (--config/--set, or the
// defaults, said so).
std::map<std::string, Config> stage_configs(const std::vector<std::string>& chain, const LogScan& scan,
                                            const Config& given, bool config_given, const std::string& in_path) {
  std::map<std::string, Config> stage_config;
  for (const auto& s : chain) {
    const auto it = scan.logged_yaml.find("gpilot-" + s);
    if (it == scan.logged_yaml.end()) {
      stage_config.emplace(s, given);
      if (!config_given)
        log_warn("%s: no CONFIG of gpilot-%s in the log: the built-in defaults (--config to choose)", s.c_str(), s.c_str());
      continue;
    }
    Config logged = Config::from_string(it->second, "the CONFIG of gpilot-" + s + " in " + in_path);
    validate_config(logged);
    stage_config.emplace(s, std::move(logged));
    log_info("%s runs with the config gpilot-%s published in the log", s.c_str(), s.c_str());
  }
  return stage_config;
}

// The replay's second pass: the chain's stages on a memq:// node on the log's clock, given the log's events one
// by one; what they publish is collected (and written to the new log, with what the options keep of the old).
class ChainReplay {
 public:
  ChainReplay(const ReplayOptions& o, std::vector<std::string> chain, std::set<std::string> inputs,
              std::set<std::string> outputs, LogScan& scan, std::map<std::string, Config> stage_config)
      : o_(o), chain_(std::move(chain)), inputs_(std::move(inputs)), outputs_(std::move(outputs)), scan_(scan),
        stage_config_(std::move(stage_config)) {
    if (!o_.out_path.empty()) {
      out_ = std::make_unique<lcm::LogFile>(o_.out_path, "w");
      if (!out_->good()) throw std::runtime_error(o_.out_path + ": cannot write log");
    }
    std::vector<std::optional<int>> threads_asked;  // once for the process: no stage sets it for another
    for (const auto& s : chain_) threads_asked.push_back(opencv_threads_of(stage_config_.at(s), s));
    set_opencv_threads(fewest_opencv_threads(threads_asked));
    for (const auto& s : chain_) {
      running_.push_back(stages().at(s).start(stage_config_.at(s), node_));
      if (stages().at(s).ticks) ticks_ = std::make_unique<ReplayTicks>(stages().at(s).ticks());
      // Both halves from the log (in a chain with the tracker, the track follows its frame at once).
      const auto& [first, second] = stages().at(s).paired;
      if (!first.empty() && inputs_.count(first) && inputs_.count(second)) pair_hold_ = std::make_unique<PairHold>(first, second);
    }
    // Messages are compared without their bus signatures: a live run's outputs were signed with its key, at
    // its times; a replay signs nothing (memq:// has no key) and strips the recorded inputs' signatures.
    for (const auto& ch : outputs_)
      node_.subscribe_raw(ch, [this](const std::string& channel, const void* data, size_t size, int64_t) {
        produced_[channel].push_back(message_of(data, size));
        if (!o_.recorded_outputs) write(now_ts_, channel, data, size);
      });
  }

  // Every event of the log between --from and --to.
  void run() {
    lcm::LogFile in(o_.in_path, "r");
    if (!in.good()) throw std::runtime_error(o_.in_path + ": cannot open log");
    int64_t first_ts = -1;
    for (const lcm::LogEvent* ev = in.readNextEvent(); ev; ev = in.readNextEvent()) {
      if (first_ts < 0) first_ts = ev->timestamp;
      const double t = (ev->timestamp - first_ts) * 1e-6;
      if (t < o_.from_s) continue;
      if (o_.to_s > 0 && t > o_.to_s) {
        // Past the cut: no input is given, but a live output of an input before it may be logged after it.
        if (o_.check && outputs_.count(ev->channel)) after_cut_[ev->channel].push_back(message_of(ev->data, static_cast<size_t>(ev->datalen)));
        continue;
      }
      ++n_events_;
      now_ts_ = ev->timestamp;
      node_.set_log_time(now_ts_);  // the stages' clock is the log's (BusNode::now)
      if (!configs_written_ && !o_.recorded_outputs) write_configs(now_ts_);
      if (ev->channel == process_channels::kConfig.name) on_config(*ev);
      else if (outputs_.count(ev->channel)) on_recorded_output(*ev);
      else if (ev->channel != process_channels::kHealth.name) on_other(*ev);  // the live processes' health is not replayed
    }
    std::fprintf(stderr, "\rgpilot-replay: %lld events, %lld inputs to %s, rejected %lld, %lld frames the live stage skipped\n",
                 static_cast<long long>(n_events_), static_cast<long long>(n_inputs_), o_.stage_arg.c_str(),
                 static_cast<long long>(node_.stats().rejected_count()), static_cast<long long>(scan_.pacing.held_back()));
    if (pair_hold_ && pair_hold_->never_paired() + static_cast<int64_t>(pair_hold_->waiting()) > 0)
      log_info("%lld inputs met no partner of their seq in the log (a frame or a track a live stage skipped): not given",
               static_cast<long long>(pair_hold_->never_paired() + static_cast<int64_t>(pair_hold_->waiting())));
    if (ticks_ && ticks_->not_logged() > 0)
      log_warn("%lld of the live stage's ticks had an input the log lacks (the logger lost it): they may differ",
               static_cast<long long>(ticks_->not_logged()));
  }

  // Prints each output's counts (and with --check its differences from the recorded ones); the differences.
  int report() {
    int differences = 0;
    for (const auto& ch : outputs_) {
      const auto& a = produced_[ch];
      const auto& b = with_late_outputs(ch);
      std::printf("%-12s new %6zu  recorded %6zu", ch.c_str(), a.size(), b.size());
      if (!o_.check) {
        std::printf("\n");
        continue;
      }
      const OutputComparison c = compare_outputs(a, b);
      const int diff = c.differing + c.only_new + c.only_recorded;
      std::printf("  differences %d", diff);
      for (size_t i = 0; i < c.first_seqs.size(); ++i)
        std::printf("%s%lld", i ? ", " : "  (seq ", static_cast<long long>(c.first_seqs[i]));
      std::printf("%s", c.first_seqs.empty() ? "" : ")");
      if (c.only_new || c.only_recorded)
        std::printf("  [%d not in the log (lost by the logger?), %d not replayed]", c.only_new, c.only_recorded);
      std::printf("\n");
      differences += diff;
    }
    if (o_.check) std::printf("%d differences\n", differences);
    return differences;
  }

 private:
  static std::vector<uint8_t> message_of(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    return std::vector<uint8_t>(p, p + message_size_of(data, size));
  }

  void write(int64_t ts, const std::string& ch, const void* data, size_t size) {
    if (!out_) return;
    lcm::LogEvent ev{};
    ev.eventnum = eventnum_++;
    ev.timestamp = ts;
    ev.channel = ch;
    ev.datalen = static_cast<int32_t>(size);
    ev.data = const_cast<void*>(data);
    out_->writeEvent(&ev);
  }
  void write(const lcm::LogEvent& ev) { write(ev.timestamp, ev.channel, ev.data, static_cast<size_t>(ev.datalen)); }

  // The new log carries the config each replayed stage ran with, as a live run's does.
  void write_configs(int64_t ts) {
    for (const auto& s : chain_) {
      config_t c{};
      c.utime = ts;
      c.process = "gpilot-" + s;
      c.yaml = effective_config_yaml(stage_config_.at(s));
      std::vector<uint8_t> bytes(static_cast<size_t>(c.getEncodedSize()));
      c.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
      write(ts, process_channels::kConfig.name, bytes.data(), bytes.size());
    }
    configs_written_ = true;
  }

  // A CONFIG: a replayed stage's is replaced by the one it replays with (kept with --recorded-outputs).
  void on_config(const lcm::LogEvent& ev) {
    config_t c{};
    const bool replayed = c.decode(ev.data, 0, ev.datalen) > 0 && c.process.rfind("gpilot-", 0) == 0 &&
                          std::find(chain_.begin(), chain_.end(), c.process.substr(7)) != chain_.end();
    if ((replayed && o_.recorded_outputs) || (!replayed && !o_.inputs_only)) write(ev);
  }

  // The recorded outputs of ch, and those logged after --to that the replay also gave (of inputs before the cut).
  const std::vector<std::vector<uint8_t>>& with_late_outputs(const std::string& ch) {
    std::vector<std::vector<uint8_t>>& b = recorded_[ch];
    std::set<std::pair<int64_t, int64_t>> given;
    for (const auto& m : produced_[ch]) given.emplace(utime_of(m), seq_of(m));
    for (auto& m : after_cut_[ch])
      if (given.count({utime_of(m), seq_of(m)})) b.push_back(std::move(m));
    after_cut_[ch].clear();
    return b;
  }

  // What a live stage sent: kept to compare with; for a timer-driven stage, where its timer fired.
  void on_recorded_output(const lcm::LogEvent& ev) {
    recorded_[ev.channel].push_back(message_of(ev.data, static_cast<size_t>(ev.datalen)));
    if (o_.recorded_outputs) write(ev);
    if (!ticks_ || ev.channel != ticks_->output()) return;
    // The live stage's timer fired here: first the inputs it had, then the tick at its own instant.
    const int64_t tick_utime = ticks_->tick(recorded_[ev.channel].back(), [&](const std::string& ch, int64_t ts,
                                                                             const std::vector<uint8_t>& bytes) {
      node_.set_log_time(ts);
      node_.publish_raw(ch, bytes.data(), bytes.size());
      node_.drain();
    });
    if (tick_utime >= 0) node_.run_timers_at(tick_utime);
    node_.drain();
    node_.set_log_time(now_ts_);
  }

  // Any other event: written as the options say; an input of the chain given to it, when the live stage had it
  // (pacing), in the order the live stage had it (aligned inits, pairs, ticks).
  void on_other(const lcm::LogEvent& ev) {
    namespace tc = tracker_channels;
    const bool input = inputs_.count(ev.channel) > 0;
    if (input || !o_.inputs_only) write(ev);
    if (!input) return;
    const auto* p = static_cast<const uint8_t*>(ev.data);
    const int64_t seq = seq_of_event(ev);
    if (scan_.align_inits && ev.channel == tc::kTrackerInit.name && aligned_init(ev) && scan_.align.frame_of(next_init_++))
      return;  // given before the frame it took effect on
    if (!scan_.pacing.give(ev.channel, seq)) return;
    ++n_inputs_;
    if (scan_.align_inits && ev.channel == tc::kCamera.name)
      for (const size_t i : scan_.align.due_before(seq)) {
        const LogScan::LoggedInit& init = scan_.inits_logged[i];
        node_.set_log_time(init.timestamp);
        node_.publish_raw(tc::kTrackerInit.name, init.bytes.data(), init.bytes.size());
        node_.drain();
        node_.set_log_time(now_ts_);
      }
    if (pair_hold_ && pair_hold_->pairs(ev.channel)) {
      for (const auto& m : pair_hold_->add(ev.channel, seq, ev.timestamp, std::vector<uint8_t>(p, p + ev.datalen))) {
        node_.set_log_time(m.timestamp);
        node_.publish_raw(m.channel, m.bytes.data(), m.bytes.size());
        node_.drain();
      }
      node_.set_log_time(now_ts_);
      return;
    }
    if (ticks_ && ticks_->keyed(ev.channel)) {
      ticks_->hold(ev.channel, ev.timestamp, std::vector<uint8_t>(p, p + ev.datalen));
      return;
    }
    node_.publish_raw(ev.channel, ev.data, static_cast<size_t>(ev.datalen));
    node_.drain();
    if (n_inputs_ % 200 == 0) std::fprintf(stderr, "\rgpilot-replay: %lld input messages", static_cast<long long>(n_inputs_));
  }

  const ReplayOptions& o_;
  const std::vector<std::string> chain_;
  const std::set<std::string> inputs_, outputs_;
  LogScan& scan_;
  const std::map<std::string, Config> stage_config_;
  std::unique_ptr<lcm::LogFile> out_;
  int64_t eventnum_ = 0;
  BusNode node_{"gpilot-replay", "memq://"};
  std::vector<std::shared_ptr<void>> running_;
  std::unique_ptr<ReplayTicks> ticks_;
  std::unique_ptr<PairHold> pair_hold_;
  std::map<std::string, std::vector<std::vector<uint8_t>>> produced_, recorded_, after_cut_;
  int64_t now_ts_ = 0, n_events_ = 0, n_inputs_ = 0;
  size_t next_init_ = 0;
  bool configs_written_ = false;
};

int run_replay(const Config& config, bool config_given, const ReplayOptions& o) {
  const std::vector<std::string> chain = parse_chain(o.stage_arg);
  std::set<std::string> outputs, inputs;
  for (const auto& s : chain)
    for (const auto& ch : stages().at(s).outputs) outputs.insert(ch);
  for (const auto& s : chain)
    for (const auto& ch : stages().at(s).inputs)
      if (!outputs.count(ch)) inputs.insert(ch);
  // A stage replays with its own run's config unless --config or --set chose one.
  LogScan scan = scan_log(o, chain, inputs, !config_given);
  auto stage_config = stage_configs(chain, scan, config, config_given, o.in_path);
  ChainReplay replay(o, chain, inputs, outputs, scan, std::move(stage_config));
  replay.run();
  const int differences = replay.report();
  return o.check && differences ? 1 : 0;
}

}  // namespace
}  // namespace gpilot

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-replay",
                 "Run a stage's code over an LCM log, faster than real time; write a log with the original inputs and\n"
                 "the new outputs; with --check, print where the new outputs differ from the recorded ones.\n"
                 "Stages: tracker (CAMERA, TRACKER_INIT -> USER_TRACK), hands (CAMERA, USER_TRACK -> HAND_OBS),\n"
                 "decide (HAND_OBS -> GESTURE_CMD), flight (GESTURE_CMD, USER_TRACK, VEHICLE_STATE, AUTOPILOT,\n"
                 "FLIGHT_CONTROL -> FLIGHT_SETPOINT: gpilot-flight's service with its timer fired at each recorded\n"
                 "setpoint's time; the vehicle's states and what the autopilot said come from the log; alone, not in a chain), or a chain such as tracker,hands,decide.");
  ReplayOptions o;
  cli.app().add_option("log", o.in_path, "the recorded LCM log")->required();
  cli.app().add_option("--stage", o.stage_arg, "stage or comma-separated chain: tracker, hands, decide, flight")->required();
  cli.app().add_option("--out", o.out_path, "write the new log here");
  cli.app().add_flag("--check", o.check, "compare the new outputs with the recorded ones (exit 1 on any difference)");
  cli.app().add_option("--from", o.from_s, "start this many seconds after the log's first event")->check(CLI::NonNegativeNumber);
  cli.app().add_option("--to", o.to_s, "stop this many seconds after the log's first event (0 = the end); --check finds the outputs of the inputs given after it too")->check(CLI::NonNegativeNumber);
  cli.app().add_flag("--inputs-only", o.inputs_only, "the new log holds only the stages' inputs and outputs (small logs)");
  cli.app().add_flag("--recorded-outputs", o.recorded_outputs,
                     "the new log holds the recorded outputs and the stages' logged CONFIG, not the replay's: a cut of\n"
                     "a live run, whose replay is then checked against what the live stages sent (tests/replay)");
  cli.app().add_flag("--all-frames", o.all_frames,
                     "give the stages every recorded frame (default: only those the live stages processed, i.e. whose\n"
                     "USER_TRACK / HAND_OBS the log records; a log without those outputs gives every frame)");
  return cli.run(argc, argv, [&](const Config& config) -> int { return run_replay(config, cli.config_given(), o); });
}
