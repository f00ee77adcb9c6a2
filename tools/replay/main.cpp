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
  std::string in_path, out_path, stage_arg;
  bool check = false, inputs_only = false, all_frames = false, recorded_outputs = false;
  double from_s = 0, to_s = 0;
  cli.app().add_option("log", in_path, "the recorded LCM log")->required();
  cli.app().add_option("--stage", stage_arg, "stage or comma-separated chain: tracker, hands, decide, flight")->required();
  cli.app().add_option("--out", out_path, "write the new log here");
  cli.app().add_flag("--check", check, "compare the new outputs with the recorded ones (exit 1 on any difference)");
  cli.app().add_option("--from", from_s, "start this many seconds after the log's first event")->check(CLI::NonNegativeNumber);
  cli.app().add_option("--to", to_s, "stop this many seconds after the log's first event (0 = the end)")->check(CLI::NonNegativeNumber);
  cli.app().add_flag("--inputs-only", inputs_only, "the new log holds only the stages' inputs and outputs (small logs)");
  cli.app().add_flag("--recorded-outputs", recorded_outputs,
                     "the new log holds the recorded outputs and the stages' logged CONFIG, not the replay's: a cut of\n"
                     "a live run, whose replay is then checked against what the live stages sent (tests/replay)");
  cli.app().add_flag("--all-frames", all_frames,
                     "give the stages every recorded frame (default: only those the live stages processed, i.e. whose\n"
                     "USER_TRACK / HAND_OBS the log records; a log without those outputs gives every frame)");
  return cli.run(argc, argv, [&](const Config& config) -> int {
    std::vector<std::string> chain;
    std::stringstream ss(stage_arg);
    for (std::string s; std::getline(ss, s, ',');) {
      if (!stages().count(s)) throw std::invalid_argument("unknown stage '" + s + "' (tracker, hands, decide, flight)");
      chain.push_back(s);
    }
    // A timer-driven stage is given its inputs in the order the live one had them, which only the log knows.
    for (const auto& s : chain)
      if (stages().at(s).ticks && chain.size() > 1)
        throw std::invalid_argument("stage '" + s + "' replays alone (its inputs come from the log, in the order it had them)");
    std::set<std::string> outputs, inputs;
    for (const auto& s : chain)
      for (const auto& o : stages().at(s).outputs) outputs.insert(o);
    for (const auto& s : chain)
      for (const auto& i : stages().at(s).inputs)
        if (!outputs.count(i)) inputs.insert(i);

    // The frames the live stages processed (ReplayPacing): a first pass over the log records their outputs' seqs.
    ReplayPacing pacing;
    if (!all_frames)
      for (const auto& s : chain)
        for (const auto& [input, output] : stages().at(s).paced) pacing.add_rule(input, output);
    // The same pass finds the config each live stage published on CONFIG when it started (the first one of its
    // process name): a stage replays with its own run's config unless --config or --set chose one.
    std::map<std::string, std::string> logged_yaml;  // process -> YAML
    // A replayed tracker given the log's manual boxes: each before the frame the live one started it on (InitAlign).
    namespace tc = tracker_channels;
    const bool align_inits = std::find(chain.begin(), chain.end(), "tracker") != chain.end() &&
                             inputs.count(tc::kTrackerInit.name) && inputs.count(tc::kCamera.name);
    InitAlign align;
    std::vector<std::vector<uint8_t>> inits_logged;  // every aligned init's bytes, in log order
    {
      const std::set<std::string> paced_outputs = pacing.output_channels();
      lcm::LogFile scan(in_path, "r");
      if (!scan.good()) throw std::runtime_error(in_path + ": cannot open log");
      int32_t last_track_id = -1;
      int8_t last_status = -1;
      for (const lcm::LogEvent* ev = scan.readNextEvent(); ev; ev = scan.readNextEvent()) {
        if (align_inits) {
          if (ev->channel == tc::kCamera.name) {
            align.frame(seq_of_event(*ev));
          } else if (ev->channel == tc::kUserTrack.name) {
            user_track_t t{};
            if (t.decode(ev->data, 0, ev->datalen) > 0) {
              const bool new_track = t.track_id != last_track_id;
              if (t.init_source == user_track_t::INIT_MANUAL && new_track)
                align.manual_start(t.seq, {t.box[0], t.box[1], t.box[2], t.box[3]});
              else if (last_status == user_track_t::STATUS_TRACKING && (t.status != user_track_t::STATUS_TRACKING || new_track))
                align.dropped(t.seq);
              last_track_id = t.track_id;
              last_status = t.status;
            }
          } else if (ev->channel == tc::kTrackerInit.name) {
            if (const auto m = aligned_init(*ev)) {
              if (m->command == tracker_init_t::COMMAND_SET_BOX) align.set_box({m->box[0], m->box[1], m->box[2], m->box[3]});
              else align.reset();
              const auto* p = static_cast<const uint8_t*>(ev->data);
              inits_logged.emplace_back(p, p + ev->datalen);
            }
          }
        }
        if (paced_outputs.count(ev->channel)) {
          pacing.recorded(ev->channel, seq_of_event(*ev));
        } else if (!cli.config_given() && ev->channel == process_channels::kConfig.name) {
          config_t c{};
          if (c.decode(ev->data, 0, ev->datalen) > 0 && check_message(c).empty()) logged_yaml.emplace(c.process, c.yaml);
        }
      }
    }
    std::map<std::string, Config> stage_config;
    for (const auto& s : chain) {
      const auto it = logged_yaml.find("gpilot-" + s);
      if (it == logged_yaml.end()) {
        stage_config.emplace(s, config);
        if (!cli.config_given())
          log_warn("%s: no CONFIG of gpilot-%s in the log: the built-in defaults (--config to choose)", s.c_str(), s.c_str());
        continue;
      }
      Config logged = Config::from_string(it->second, "the CONFIG of gpilot-" + s + " in " + in_path);
      validate_config(logged);
      stage_config.emplace(s, std::move(logged));
      log_info("%s runs with the config gpilot-%s published in the log", s.c_str(), s.c_str());
    }
    if (align_inits) align.finish();
    size_t next_init = 0;
    lcm::LogFile in(in_path, "r");
    if (!in.good()) throw std::runtime_error(in_path + ": cannot open log");
    std::unique_ptr<lcm::LogFile> out;
    if (!out_path.empty()) {
      out = std::make_unique<lcm::LogFile>(out_path, "w");
      if (!out->good()) throw std::runtime_error(out_path + ": cannot write log");
    }
    int64_t eventnum = 0;
    auto write = [&](int64_t ts, const std::string& ch, const void* data, size_t size) {
      if (!out) return;
      lcm::LogEvent ev{};
      ev.eventnum = eventnum++;
      ev.timestamp = ts;
      ev.channel = ch;
      ev.datalen = static_cast<int32_t>(size);
      ev.data = const_cast<void*>(data);
      out->writeEvent(&ev);
    };

    BusNode node("gpilot-replay", "memq://");
    int64_t now_ts = 0;
    std::vector<std::shared_ptr<void>> running;
    std::unique_ptr<ReplayTicks> ticks;
    std::unique_ptr<PairHold> pair_hold;
    bool configs_written = false;
    for (const auto& s : chain) {
      running.push_back(stages().at(s).start(stage_config.at(s), node));
      if (stages().at(s).ticks) ticks = std::make_unique<ReplayTicks>(stages().at(s).ticks());
      // Both halves from the log (in a chain with the tracker, the track follows its frame at once).
      const auto& [first, second] = stages().at(s).paired;
      if (!first.empty() && inputs.count(first) && inputs.count(second)) pair_hold = std::make_unique<PairHold>(first, second);
    }
    // The new log carries the config each replayed stage ran with, as a live run's does.
    auto write_configs = [&](int64_t ts) {
      for (const auto& s : chain) {
        config_t c{};
        c.utime = ts;
        c.process = "gpilot-" + s;
        c.yaml = effective_config_yaml(stage_config.at(s));
        std::vector<uint8_t> bytes(static_cast<size_t>(c.getEncodedSize()));
        c.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
        write(ts, process_channels::kConfig.name, bytes.data(), bytes.size());
      }
      configs_written = true;
    };
    // Messages are compared without their bus signatures: a live run's outputs were signed with its key, at
    // its times; a replay signs nothing (memq:// has no key) and strips the recorded inputs' signatures.
    std::map<std::string, std::vector<std::vector<uint8_t>>> produced, recorded;
    const auto message_of = [](const void* data, size_t size) {
      const auto* p = static_cast<const uint8_t*>(data);
      return std::vector<uint8_t>(p, p + message_size_of(data, size));
    };
    for (const auto& o : outputs)
      node.subscribe_raw(o, [&](const std::string& ch, const void* data, size_t size, int64_t) {
        produced[ch].push_back(message_of(data, size));
        if (!recorded_outputs) write(now_ts, ch, data, size);
      });

    int64_t n_events = 0, n_inputs = 0, first_ts = -1;
    for (const lcm::LogEvent* ev = in.readNextEvent(); ev; ev = in.readNextEvent()) {
      if (first_ts < 0) first_ts = ev->timestamp;
      const double t = (ev->timestamp - first_ts) * 1e-6;
      if (t < from_s) continue;
      if (to_s > 0 && t > to_s) break;
      ++n_events;
      now_ts = ev->timestamp;
      const auto* p = static_cast<const uint8_t*>(ev->data);
      node.set_log_time(now_ts);  // the stages' clock is the log's (BusNode::now)
      if (!configs_written && !recorded_outputs) write_configs(now_ts);
      if (ev->channel == process_channels::kConfig.name) {  // a replayed stage's is replaced by the one it replays with
        config_t c{};
        const bool replayed = c.decode(ev->data, 0, ev->datalen) > 0 && c.process.rfind("gpilot-", 0) == 0 &&
                              std::find(chain.begin(), chain.end(), c.process.substr(7)) != chain.end();
        if ((replayed && recorded_outputs) || (!replayed && !inputs_only))
          write(ev->timestamp, ev->channel, ev->data, static_cast<size_t>(ev->datalen));
        continue;
      }
      if (outputs.count(ev->channel)) {
        recorded[ev->channel].push_back(message_of(p, static_cast<size_t>(ev->datalen)));
        if (recorded_outputs) write(ev->timestamp, ev->channel, ev->data, static_cast<size_t>(ev->datalen));
        if (ticks && ev->channel == ticks->output()) {
          // The live stage's timer fired here: first the inputs it had, then the tick at its own instant.
          const int64_t tick_utime = ticks->tick(recorded[ev->channel].back(), [&](const std::string& ch, int64_t ts,
                                                                                  const std::vector<uint8_t>& bytes) {
            node.set_log_time(ts);
            node.publish_raw(ch, bytes.data(), bytes.size());
            node.drain();
          });
          if (tick_utime >= 0) node.run_timers_at(tick_utime);
          node.drain();
          node.set_log_time(now_ts);
        }
        continue;
      }
      if (ev->channel == process_channels::kHealth.name) continue;  // the live processes' health is not part of a replay
      const bool input = inputs.count(ev->channel) > 0;
      if (input || !inputs_only) write(ev->timestamp, ev->channel, ev->data, static_cast<size_t>(ev->datalen));
      if (!input) continue;
      const int64_t seq = seq_of_event(*ev);
      if (align_inits && ev->channel == tc::kTrackerInit.name && aligned_init(*ev) && align.frame_of(next_init++))
        continue;  // given before the frame it took effect on
      if (!pacing.give(ev->channel, seq)) continue;
      ++n_inputs;
      if (align_inits && ev->channel == tc::kCamera.name)
        for (const size_t i : align.due_before(seq)) {
          node.publish_raw(tc::kTrackerInit.name, inits_logged[i].data(), inits_logged[i].size());
          node.drain();
        }
      if (pair_hold && pair_hold->pairs(ev->channel)) {
        for (const auto& m : pair_hold->add(ev->channel, seq, ev->timestamp, std::vector<uint8_t>(p, p + ev->datalen))) {
          node.set_log_time(m.timestamp);
          node.publish_raw(m.channel, m.bytes.data(), m.bytes.size());
          node.drain();
        }
        node.set_log_time(now_ts);
        continue;
      }
      if (ticks && ticks->keyed(ev->channel)) {
        ticks->hold(ev->channel, ev->timestamp, std::vector<uint8_t>(p, p + ev->datalen));
        continue;
      }
      node.publish_raw(ev->channel, ev->data, static_cast<size_t>(ev->datalen));
      node.drain();
      if (n_inputs % 200 == 0) std::fprintf(stderr, "\rgpilot-replay: %lld input messages", static_cast<long long>(n_inputs));
    }
    std::fprintf(stderr, "\rgpilot-replay: %lld events, %lld inputs to %s, rejected %lld, %lld frames the live stage skipped\n",
                 static_cast<long long>(n_events), static_cast<long long>(n_inputs), stage_arg.c_str(),
                 static_cast<long long>(node.stats().rejected_count()), static_cast<long long>(pacing.held_back()));
    if (pair_hold && pair_hold->never_paired() + static_cast<int64_t>(pair_hold->waiting()) > 0)
      log_info("%lld inputs met no partner of their seq in the log (a frame or a track a live stage skipped): not given",
               static_cast<long long>(pair_hold->never_paired() + static_cast<int64_t>(pair_hold->waiting())));
    if (ticks && ticks->not_logged() > 0)
      log_warn("%lld of the live stage's ticks had an input the log lacks (the logger lost it): they may differ",
               static_cast<long long>(ticks->not_logged()));
    int differences = 0;
    for (const auto& o : outputs) {
      const auto& a = produced[o];
      const auto& b = recorded[o];
      std::printf("%-12s new %6zu  recorded %6zu", o.c_str(), a.size(), b.size());
      if (!check) {
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
    if (check) std::printf("%d differences\n", differences);
    return check && differences ? 1 : 0;
  });
}
