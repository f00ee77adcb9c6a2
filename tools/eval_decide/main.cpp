// gpilot-eval-decide: the decide stage's speed and robustness over logs with HAND_OBS and GROUND_TRUTH, for a
// set of configurations (--sweep, --variant; the paper's Alg. 3 is always one of them). Per configuration:
// reaction time (true gesture change -> first GESTURE_CMD with the new command), frames still carrying the old
// command, and false commands per minute, at the decide stage's output and as the flight stage flies them
// (its command spacing included). A table, or --json; --plot draws false commands against reaction time.
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/yaml.h>

#include "config.hpp"
#include "decide_eval.hpp"
#include "json_out.hpp"
#include "log.hpp"
#include "log_reader.hpp"
#include "overlay.hpp"
#include "service_cli.hpp"

namespace gpilot {
namespace {

constexpr const char* kName = "gpilot-eval-decide";

// One configuration: a name and its section.key=value assignments over the loaded config.
struct Variant {
  std::string name;
  std::vector<std::string> sets;
};

// The paper's Alg. 3 and the paper's 600 ms spacing, whatever the loaded config says.
Variant paper_variant() {
  return {"paper", {"decide.rule=paper", "decide.buffer_size=60", "decide.out_threshold=30", "decide.front_threshold=30",
                    "decide.lambda4=0.5", "flight.command_spacing_s=0.6"}};
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string part; std::getline(ss, part, sep);)
    if (!part.empty()) out.push_back(part);
  return out;
}

// Overwrites params' keys named by the assignments of `section` ("decide.key=value", "decide.group.key=value"),
// through the same reader that checks config files (unknown keys and out-of-range values throw ConfigError).
template <class P>
void apply(P& params, const char* section, const std::vector<std::string>& sets) {
  YAML::Node node(YAML::NodeType::Map);
  for (const auto& a : sets) {
    const auto eq = a.find('=');
    if (eq == std::string::npos) throw ConfigError(a + ": expected section.key=value");
    const auto path = split(a.substr(0, eq), '.');
    if (path.size() < 2) throw ConfigError(a + ": expected section.key=value");
    if (path[0] != "decide" && path[0] != "flight") throw ConfigError(a + ": only decide.* and flight.* can vary here");
    if (path[0] != section) continue;
    YAML::Node n = node;
    for (size_t i = 1; i + 1 < path.size(); ++i) {
      if (!n[path[i]]) n[path[i]] = YAML::Node(YAML::NodeType::Map);
      n = n[path[i]];
    }
    n[path.back()] = YAML::Load(a.substr(eq + 1));
  }
  ParamReader reader(node, section);
  params.visit(reader);
  reader.finish();
  check_params(params, section);  // the choices and cross-field rules a config file must obey too
}

struct Result {
  Variant variant;
  Score decided, flown;                    // pooled over the logs
  std::vector<Score> decided_per_log, flown_per_log;
  bool live = false;                       // a live run's recorded commands, not a configuration re-run
};

// The plot's axis labels.
std::string num(double v, const char* fmt) {
  char b[32];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

// One Score as --json writes it, with the digits it always had (s and minutes: 3, percent: 2); no reaction -> null.
json score_json(const Score& s) {
  const double pct_old = s.frames ? 100.0 * s.old_frames / s.frames : 0.0;
  const double pct_wrong = s.frames ? 100.0 * s.wrong_frames / s.frames : 0.0;
  return {{"frames", s.frames},
          {"minutes", rounded(s.minutes, 3)},
          {"changes", s.changes},
          {"missed", s.missed},
          {"reaction_median_s", rounded(s.reaction_median_s(), 3)},
          {"reaction_max_s", rounded(s.reaction_max_s(), 3)},
          {"reaction_median_frames", s.reaction_median_frames()},
          {"reaction_max_frames", s.reaction_max_frames()},
          {"old_frames", s.old_frames},
          {"old_percent", rounded(pct_old, 2)},
          {"wrong_frames", s.wrong_frames},
          {"wrong_percent", rounded(pct_wrong, 2)},
          {"false_at_rest", s.false_at_rest},
          {"false_at_rest_frames", s.false_at_rest_frames},
          {"confused", s.confused},
          {"confused_frames", s.confused_frames},
          {"false_per_minute", rounded(s.false_per_minute(), 3)}};
}

std::string row(const std::string& name, const Score& s) {
  char b[256];
  std::snprintf(b, sizeof b, "%-26s %5.2f (%3d) %5.2f (%3d) %3d/%-3d %5lld %5.1f%% %5.1f%% %4d %4d %6.2f", name.c_str(),
                s.reaction_median_s(), s.reaction_median_frames(), s.reaction_max_s(), s.reaction_max_frames(), s.missed,
                s.changes, static_cast<long long>(s.old_frames), s.frames ? 100.0 * s.old_frames / s.frames : 0.0,
                s.frames ? 100.0 * s.wrong_frames / s.frames : 0.0, s.false_at_rest, s.confused, s.false_per_minute());
  return b;
}

// False commands per minute against the median reaction (at GESTURE_CMD: filled; as flown: open, joined).
void plot(const std::string& file, const std::vector<Result>& results) {
  const int w = 900, h = 600, left = 80, right = 30, top = 40, bottom = 70;
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  double xmax = 0.5, ymax = 0.5;
  for (const auto& r : results) {
    for (const Score* s : {&r.decided, &r.flown}) {
      if (std::isfinite(s->reaction_median_s())) xmax = std::max(xmax, s->reaction_median_s());
      ymax = std::max(ymax, s->false_per_minute());
    }
  }
  xmax = std::ceil(xmax * 1.1 * 4) / 4;
  ymax = std::ceil(ymax * 1.15);
  auto px = [&](double x, double y) {
    return cv::Point(left + static_cast<int>(x / xmax * (w - left - right)),
                     h - bottom - static_cast<int>(y / ymax * (h - top - bottom)));
  };
  const cv::Scalar grey(200, 200, 200), black(0, 0, 0);
  for (double x = 0; x <= xmax + 1e-9; x += 0.25) {
    cv::line(img, px(x, 0), px(x, ymax), grey);
    cv::putText(img, num(x, "%.2f"), px(x, 0) + cv::Point(-15, 20), cv::FONT_HERSHEY_SIMPLEX, 0.45, black);
  }
  const double ystep = ymax > 10 ? std::ceil(ymax / 10) : ymax > 2 ? 1.0 : 0.25;
  for (double y = 0; y <= ymax + 1e-9; y += ystep) {
    cv::line(img, px(0, y), px(xmax, y), grey);
    cv::putText(img, num(y, "%.2f"), px(0, y) + cv::Point(-55, 5), cv::FONT_HERSHEY_SIMPLEX, 0.45, black);
  }
  // The bar: median reaction <= 0.5 s with no false command.
  cv::line(img, px(0.5, 0), px(0.5, ymax), cv::Scalar(0, 160, 0), 1, cv::LINE_AA);
  cv::putText(img, "median reaction, s (filled: GESTURE_CMD, open: as flown, 600 ms spacing etc.)",
              cv::Point(left, h - 20), cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
  cv::putText(img, "false + confused commands per minute", cv::Point(10, 25), cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
  for (size_t i = 0; i < results.size(); ++i) {
    const auto& r = results[i];
    const cv::Scalar c = cv::Scalar((i * 97) % 200, (i * 57 + 80) % 200, (i * 151 + 40) % 220);
    if (!std::isfinite(r.decided.reaction_median_s())) continue;
    const cv::Point a = px(r.decided.reaction_median_s(), r.decided.false_per_minute());
    cv::circle(img, a, 5, c, cv::FILLED, cv::LINE_AA);
    // Points crowd near the axis: labels step up in three rows.
    cv::putText(img, r.variant.name, a + cv::Point(7, -6 - 13 * static_cast<int>(i % 3)), cv::FONT_HERSHEY_SIMPLEX, 0.4, c, 1,
                cv::LINE_AA);
    if (std::isfinite(r.flown.reaction_median_s())) {
      const cv::Point b = px(r.flown.reaction_median_s(), r.flown.false_per_minute());
      cv::circle(img, b, 5, c, 1, cv::LINE_AA);
      cv::line(img, a, b, c, 1, cv::LINE_AA);
    }
  }
  if (!cv::imwrite(file, img)) throw std::runtime_error(file + ": cannot write the plot");
}

std::string frames_or_missed(int frames) { return frames < 0 ? "(missed)" : std::to_string(frames) + " frames"; }

void trace(const EvalLog& log, const StageRun& run) {
  const int64_t t0 = log.frames.empty() ? 0 : log.frames.front().obs.utime;
  std::printf("%8s %6s %4s %4s %4s %8s %8s %4s %7s %7s %4s\n", "t_s", "seq", "gest", "exp", "kind", "vx", "vy", "cmd",
              "dx", "dy", "flown");
  for (size_t i = 0; i < log.frames.size(); ++i) {
    const auto& f = log.frames[i];
    std::printf("%8.2f %6lld %4d %4d %4d %8.1f %8.1f %4d %7.3f %7.3f %4d\n", (f.obs.utime - t0) * 1e-6,
                static_cast<long long>(f.obs.seq), f.gesture, f.expected_mode, static_cast<int>(f.obs.kind), f.obs.vector.x,
                f.obs.vector.y, run.decided[i].mode, run.decided[i].dir[0], run.decided[i].dir[1], run.flown[i].mode);
  }
}

}  // namespace
}  // namespace gpilot

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli(kName,
                 "Runs the decide stage's core (and the flight stage's command adoption) over the HAND_OBS of logs with\n"
                 "GROUND_TRUTH, for each configuration, and prints per configuration: reaction time (true gesture change\n"
                 "-> first command with the new mode, FINE within --fine-angle-deg of the pointed direction; median and\n"
                 "max, s and frames), changes missed, frames still carrying the old command, frames with any wrong\n"
                 "command, and false commands (not HOVER while the user rests; or another motion than the one asked)\n"
                 "per minute. First at GESTURE_CMD, then as the flight stage flies it. The paper's Alg. 3 is always\n"
                 "one configuration (--no-paper drops it). Logs: gpilot-capture --synthetic + gpilot-replay --stage\n"
                 "tracker,hands, or a ./deploy/run log; a live run's log also gives its own recorded GESTURE_CMD and\n"
                 "FLIGHT_SETPOINT as the first row (\"as flown\": the setpoint's mode when the next frame was logged).");
  std::vector<std::string> logs, sweeps, variants;
  std::string plot_file;
  bool print_json = false, no_paper = false, do_trace = false, list_changes = false;
  ScoreRules rules;
  cli.app().add_option("logs", logs, "LCM logs with HAND_OBS and GROUND_TRUTH")->required();
  cli.app().add_option("--sweep", sweeps, "section.key=v1,v2,...: one configuration per value (several: every combination)");
  cli.app().add_option("--variant", variants, "\"NAME section.key=v section.key=v ...\": a named configuration");
  cli.app().add_flag("--no-paper", no_paper, "leave out the paper's Alg. 3 (rule paper, 60/30/30, 600 ms spacing)");
  cli.app().add_flag("--json", print_json, "one JSON object on stdout instead of the table");
  cli.app().add_option("--plot", plot_file, "write a PNG of false commands per minute against median reaction time");
  cli.app().add_flag("--trace", do_trace, "print every frame of the first log for the first configuration, then stop");
  cli.app().add_flag("--changes", list_changes, "list every true change with its reaction (per configuration and log)");
  cli.app().add_option("--turn-deg", rules.turn_deg, "an OUT gesture turning more than this is a new gesture")->capture_default_str();
  cli.app().add_option("--min-turn-s", rules.min_turn_s, "a turned OUT piece shorter than this joins the next one")->capture_default_str();
  cli.app().add_option("--fine-angle-deg", rules.fine_angle_deg, "FINE within this angle of the truth is right")->capture_default_str();
  return cli.run(argc, argv, [&](const Config& config) -> int {
    // Configurations: the named variants, then every combination of the sweeps, else the config as given.
    std::vector<Variant> configs;
    if (!no_paper) configs.push_back(paper_variant());
    for (const auto& v : variants) {
      auto parts = split(v, ' ');
      if (parts.empty()) throw ConfigError("--variant: empty");
      configs.push_back({parts[0], std::vector<std::string>(parts.begin() + 1, parts.end())});
    }
    std::vector<Variant> combos{{"", {}}};
    for (const auto& s : sweeps) {
      const auto eq = s.find('=');
      if (eq == std::string::npos) throw ConfigError("--sweep " + s + ": expected section.key=v1,v2,...");
      const std::string key = s.substr(0, eq);
      std::vector<Variant> next;
      for (const auto& c : combos)
        for (const auto& value : split(s.substr(eq + 1), ',')) {
          Variant n = c;
          const std::string short_key = key.substr(key.find('.') + 1);
          n.name += (n.name.empty() ? "" : " ") + short_key + "=" + value;
          n.sets.push_back(key + "=" + value);
          next.push_back(n);
        }
      combos = next;
    }
    if (!sweeps.empty()) configs.insert(configs.end(), combos.begin(), combos.end());
    if (variants.empty() && sweeps.empty()) configs.push_back({"config", {}});

    const auto base_decide = config.section<DecideParams>("decide");
    const auto base_flight = config.section<FlightParams>("flight");
    std::vector<EvalLog> data;
    for (const auto& path : logs) {
      log_info("reading %s", path.c_str());
      data.push_back(read_eval_log(path));
      if (data.back().hand_obs_without_truth)
        log_warn("%s: %lld HAND_OBS without GROUND_TRUTH left out", path.c_str(),
                 static_cast<long long>(data.back().hand_obs_without_truth));
    }
    // A live run's own GESTURE_CMD and FLIGHT_SETPOINT, when every log has them: measured, not re-run.
    std::vector<Result> results;
    bool recorded = true;
    for (const auto& log : data) recorded = recorded && !log.recorded_cmd.empty() && !log.recorded_flown.empty();
    if (recorded) {
      Result r{{"recorded (live run)", {}}, {}, {}, {}, {}, true};
      for (const auto& log : data) {
        const auto truth = truth_of(log);
        r.decided_per_log.push_back(score_commands(truth, log.recorded_cmd, rules));
        r.flown_per_log.push_back(score_commands(truth, log.recorded_flown, rules));
        r.decided.add(r.decided_per_log.back());
        r.flown.add(r.flown_per_log.back());
      }
      results.push_back(r);
    }
    for (size_t ci = 0; ci < configs.size(); ++ci) {
      const Variant& v = configs[ci];
      std::fprintf(stderr, "\r%s: configuration %zu of %zu", kName, ci + 1, configs.size());
      DecideParams dp = base_decide;
      FlightParams fp = base_flight;
      apply(dp, "decide", v.sets);
      apply(fp, "flight", v.sets);
      Result r{v, {}, {}, {}, {}, false};
      for (const auto& log : data) {
        const StageRun run = run_stages(log, dp, fp);
        if (do_trace) {
          trace(log, run);
          return 0;
        }
        const auto truth = truth_of(log);
        r.decided_per_log.push_back(score_commands(truth, run.decided, rules));
        r.flown_per_log.push_back(score_commands(truth, run.flown, rules));
        r.decided.add(r.decided_per_log.back());
        r.flown.add(r.flown_per_log.back());
      }
      results.push_back(r);
    }
    std::fprintf(stderr, "\n");
    if (!plot_file.empty()) plot(plot_file, results);

    if (print_json) {
      json out = {{"logs", logs},
                          {"rules",
                           {{"turn_deg", rounded(rules.turn_deg, 3)},
                            {"fine_angle_deg", rounded(rules.fine_angle_deg, 3)},
                            {"min_turn_s", rounded(rules.min_turn_s, 3)}}},
                          {"configurations", json::array()}};
      for (const auto& r : results) {
        json per_log = json::array();
        for (size_t k = 0; k < logs.size(); ++k)
          per_log.push_back({{"log", logs[k]},
                             {"gesture_cmd", score_json(r.decided_per_log[k])},
                             {"flown", score_json(r.flown_per_log[k])}});
        out["configurations"].push_back({{"name", r.variant.name},
                                         {"sets", r.variant.sets},
                                         {"gesture_cmd", score_json(r.decided)},
                                         {"flown", score_json(r.flown)},
                                         {"per_log", per_log}});
      }
      std::printf("%s\n", out.dump().c_str());
      return 0;
    }
    std::printf("%-26s %-11s %-11s %-7s %-5s %-6s %-6s %-4s %-4s %-6s\n", "configuration", "median s(fr)", "max s(fr)",
                "missed", "old", "old%", "wrong%", "rest", "conf", "false/min");
    for (const auto& r : results) {
      std::printf("%s\n", row(r.variant.name, r.decided).c_str());
      std::printf("%s\n", row(r.live ? "  FLIGHT_SETPOINT" : "  as flown", r.flown).c_str());
      for (size_t k = 0; k < logs.size(); ++k) {
        const std::string base = logs[k].substr(logs[k].find_last_of('/') + 1);
        std::printf("%s\n", row("  " + base.substr(0, 24), r.decided_per_log[k]).c_str());
        if (!list_changes) continue;
        const auto& d = r.decided_per_log[k];
        const auto& f = r.flown_per_log[k];
        const int64_t t0 = data[k].frames.front().obs.utime;
        for (size_t c = 0; c < d.change_list.size(); ++c)
          std::printf("    %7.2f s  %-7s -> %-7s  GESTURE_CMD after %s, flown after %s\n",
                      (d.change_list[c].utime - t0) * 1e-6, mode_name(d.change_list[c].from_mode),
                      mode_name(d.change_list[c].to_mode), frames_or_missed(d.change_list[c].frames).c_str(),
                      frames_or_missed(c < f.change_list.size() ? f.change_list[c].frames : -1).c_str());
        for (const auto& e : d.false_list)
          std::printf("    %7.2f s  %-7s but %-7s GESTURE_CMD for %d frames (%s)\n", (e.utime - t0) * 1e-6,
                      mode_name(e.from_mode), mode_name(e.to_mode), e.frames, e.from_mode ? "confused" : "false");
      }
    }
    return 0;
  });
}
