// gpilot-report: a run's numbers and pictures from its LCM log. Reads CAMERA, USER_TRACK, GESTURE_CMD,
// FLIGHT_SETPOINT, VEHICLE_STATE, GROUND_TRUTH and HEALTH from the log (no bus). Writes DIR/summary.json and
// DIR/trajectory.png, prints a table (or, with --json, the summary JSON) on stdout, progress on stderr.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>

#include "analyze_log.hpp"
#include "config.hpp"
#include "decide/decide_params.hpp"
#include "log.hpp"
#include "service_cli.hpp"
#include "trajectory_plot.hpp"

namespace {

constexpr const char* kName = "gpilot-report";

int report(const std::string& log_path, const std::string& out_dir, bool print_json, const gpilot::DecideParams& decide) {
  using namespace gpilot;
  const LogAnalysis a = analyse_log(log_path, settling_for(decide.rule, decide.buffer_size), kName);
  for (const auto& w : a.warnings) gpilot::log_warn("%s", w.c_str());

  const Summary& s = a.summary;
  // Indented, one member a line: summary.json is read by people and by deploy/run's line-wise sed (logger_lost);
  // --json prints the same text.
  // The log's cost on disk, per minute of camera frames (0 without frames).
  const double log_mb = static_cast<double>(std::filesystem::file_size(log_path)) * 1e-6;
  const double log_mb_per_min = s.duration_s > 0 ? std::round(log_mb / (s.duration_s / 60.0) * 10) / 10 : 0.0;
  const std::string j = summary_json(s, {{"log", log_path},
                                         {"log_mb", std::round(log_mb * 10) / 10},
                                         {"log_mb_per_minute", log_mb_per_min},
                                         {"log_events", a.events},
                                         {"decide_rule", decide.rule},
                                         {"buffer_size", decide.buffer_size},
                                         {"rejected_messages", a.rejected},
                                         {"warnings", a.warnings}})
                            .dump(2) + "\n";
  if (!out_dir.empty()) {
    namespace fs = std::filesystem;
    fs::create_directories(out_dir);
    const std::string json_path = (fs::path(out_dir) / "summary.json").string();
    std::ofstream(json_path) << j;
    const std::string png = (fs::path(out_dir) / "trajectory.png").string();
    const std::string title = "gesture-pilot run: " + fs::path(log_path).filename().string() + "  (" +
                              std::to_string(s.vehicle_states) + " vehicle states, " +
                              std::to_string(static_cast<long long>(s.duration_s + 0.5)) + " s)";
    if (!cv::imwrite(png, draw_trajectory(a.path, title))) throw std::runtime_error("cannot write " + png);
    if (!std::ifstream(json_path)) throw std::runtime_error("cannot write " + json_path);
    gpilot::log_info("wrote %s and %s", json_path.c_str(), png.c_str());
  }
  std::fputs(print_json ? j.c_str() : summary_table(s).c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "Reads a run's LCM log and writes DIR/summary.json (frames, commands per mode, per-stage rates and processing "
      "times from HEALTH, end-to-end latency, gesture accuracy against GROUND_TRUTH with a confusion matrix) and "
      "DIR/trajectory.png (the vehicle's path coloured by gesture mode). Prints a table, or the JSON with --json.",
      kName);
  std::string log, out, config_file;
  std::vector<std::string> sets;
  bool json = false;
  app.add_option("LOG", log, "the run's LCM log (lcm-logger)")->required();
  app.add_option("--out", out, "folder for summary.json and trajectory.png (created; none: stdout only)");
  app.add_flag("--json", json, "print the summary JSON on stdout instead of the table");
  app.add_option("--config", config_file, "the run's config (decide.rule and decide.buffer_size: what the accuracy leaves out after a change; default: built-in defaults)");
  app.add_option("--set", sets, "override one key: section.key=value (repeatable)");
  std::string log_level;
  gpilot::add_standard_flags(app, kName, log_level);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (!gpilot::apply_log_level(log_level)) return 2;
  try {
    const gpilot::Config config = gpilot::load_config(config_file, sets);
    const auto decide = config.section<gpilot::DecideParams>("decide");
    return report(log, out, json, decide);
  } catch (const gpilot::ConfigError& e) {
    gpilot::log_error("config error: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    gpilot::log_error("%s", e.what());
    return 1;
  }
}
