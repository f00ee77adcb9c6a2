// The command line every gpilot process shares: --config, --set, --lcm-url, --log-level, --version, --help
// with the stage's description. Config is loaded and the whole file validated before the bus is touched; a bad config
// exits with status 2, a bus that cannot start with 3, any other error with 1. A process with a bus
// publishes its effective config on CONFIG when it starts.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bus_node.hpp"
#include "config.hpp"

namespace gpilot {

class ServiceCli {
 public:
  ServiceCli(std::string name, const std::string& description);

  // Add the stage's own flags here before run().
  CLI::App& app() { return app_; }

  // Parses argv, loads the config, then calls body without a bus (tools) or with one (services).
  int run(int argc, char** argv, const std::function<int(const Config&)>& body);
  int run_node(int argc, char** argv, const std::function<int(const Config&, BusNode&)>& body);
  // What run_node does with the config before the bus starts (a stage's models loaded): whatever it throws
  // stops the process as a bad config does (status 2, the error named), before anything is sent.
  void before_bus(std::function<void(const Config&)> prepare) { before_bus_ = std::move(prepare); }

  const std::string& name() const { return name_; }
  const std::string& lcm_url() const { return lcm_url_; }
  // Whether the command line chose a config (--config or --set), over e.g. one recorded in a log.
  bool config_given() const { return !config_file_.empty() || !sets_.empty(); }

 private:
  std::string name_;
  CLI::App app_;
  std::string config_file_;
  std::vector<std::string> sets_;
  std::string lcm_url_;
  std::string log_level_;
  std::function<void(const Config&)> before_bus_;
};

// What --version prints after the program's name: `git describe --always --dirty` at build time, or the
// project version where it was built without git.
const char* gpilot_version();

// For tools with their own CLI::App: --version ("NAME VERSION") and --log-level, as ServiceCli gives them;
// after parsing, apply_log_level(level) (returns false with the reason logged for a level that is none).
void add_standard_flags(CLI::App& app, const std::string& name, std::string& log_level);
bool apply_log_level(const std::string& log_level);

// Loads a config file ("" = defaults), applies section.key=value overrides and validates every section.
Config load_config(const std::string& file, const std::vector<std::string>& sets);

}  // namespace gpilot
