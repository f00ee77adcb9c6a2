#include "service_cli.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <unistd.h>

#include "config_schema.hpp"
#include "gpilot_version.hpp"  // generated at build time (cmake/version.cmake)
#include "log.hpp"
#include "process_channels.hpp"

namespace gpilot {

Config load_config(const std::string& file, const std::vector<std::string>& sets) {
  Config config = file.empty() ? Config() : Config::from_file(file);
  for (const auto& s : sets) config.set(s);
  validate_config(config);
  return config;
}

const char* gpilot_version() { return GPILOT_VERSION; }

void add_standard_flags(CLI::App& app, const std::string& name, std::string& log_level) {
  set_log_name(name);
  app.set_version_flag("--version", name + " " + gpilot_version(), "print the program's version and exit");
  app.add_option("--log-level", log_level, "error, warn, info or debug (default: $GPILOT_LOG_LEVEL, else info)");
}

bool apply_log_level(const std::string& log_level) {
  if (!set_log_level_from_env()) {
    log_error("config error: GPILOT_LOG_LEVEL='%s' is not one of error, warn, info, debug", std::getenv("GPILOT_LOG_LEVEL"));
    return false;
  }
  if (log_level.empty()) return true;
  const auto level = parse_log_level(log_level);
  if (!level) {
    log_error("config error: --log-level '%s' is not one of error, warn, info, debug", log_level.c_str());
    return false;
  }
  set_log_level(*level);
  return true;
}

ServiceCli::ServiceCli(std::string name, const std::string& description) : name_(std::move(name)), app_(description, name_) {
  app_.add_option("--config", config_file_, "YAML config file (default: built-in defaults, as deploy/config/default.yaml)");
  app_.add_option("--set", sets_, "override one key: section.key=value (repeatable)");
  app_.add_option("--lcm-url", lcm_url_, std::string("LCM URL (default: $GPILOT_LCM_URL, else ") + kDefaultLcmUrl + ")");
  add_standard_flags(app_, name_, log_level_);
}

int ServiceCli::run(int argc, char** argv, const std::function<int(const Config&)>& body) {
  try {
    app_.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app_.exit(e);
  }
  if (!apply_log_level(log_level_)) return 2;
  try {
    const Config config = load_config(config_file_, sets_);
    return body(config);
  } catch (const ConfigError& e) {
    log_error("config error: %s", e.what());
    return 2;
  } catch (const BusError& e) {
    log_error("%s", e.what());
    return 3;
  } catch (const std::exception& e) {
    log_error("%s", e.what());
    return 1;
  }
}

int ServiceCli::run_node(int argc, char** argv, const std::function<int(const Config&, BusNode&)>& body) {
  return run(argc, argv, [&](const Config& config) {
    if (before_bus_) {
      try {
        before_bus_(config);
      } catch (const ConfigError&) {
        throw;
      } catch (const std::exception& e) {
        throw ConfigError(e.what());
      }
    }
    BusNode node(name_, resolve_lcm_url(lcm_url_), config.section<BusParams>("bus"));
    // What this process runs with, once, so that a log of the run replays with it (gpilot-replay).
    config_t c{};
    c.utime = node.now();
    c.process = name_;
    c.pid = static_cast<int32_t>(getpid());
    c.yaml = effective_config_yaml(config);
    node.publish_report(process_channels::kConfig.name, c);
    return body(config, node);
  });
}

}  // namespace gpilot
