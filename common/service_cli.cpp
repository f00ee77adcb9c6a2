#include "service_cli.hpp"

#include <cstdio>
#include <exception>
#include <unistd.h>

#include "config_schema.hpp"

namespace gpilot {

Config load_config(const std::string& file, const std::vector<std::string>& sets) {
  Config config = file.empty() ? Config() : Config::from_file(file);
  for (const auto& s : sets) config.set(s);
  validate_config(config);
  return config;
}

ServiceCli::ServiceCli(std::string name, const std::string& description) : name_(std::move(name)), app_(description, name_) {
  app_.add_option("--config", config_file_, "YAML config file (default: built-in defaults, as deploy/config/default.yaml)");
  app_.add_option("--set", sets_, "override one key: section.key=value (repeatable)");
  app_.add_option("--lcm-url", lcm_url_, std::string("LCM URL (default: $GPILOT_LCM_URL, else ") + kDefaultLcmUrl + ")");
}

int ServiceCli::run(int argc, char** argv, const std::function<int(const Config&)>& body) {
  try {
    app_.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app_.exit(e);
  }
  try {
    const Config config = load_config(config_file_, sets_);
    return body(config);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "%s: config error: %s\n", name_.c_str(), e.what());
    return 2;
  } catch (const BusError& e) {
    std::fprintf(stderr, "%s: %s\n", name_.c_str(), e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", name_.c_str(), e.what());
    return 1;
  }
}

int ServiceCli::run_node(int argc, char** argv, const std::function<int(const Config&, BusNode&)>& body) {
  return run(argc, argv, [&](const Config& config) {
    BusNode node(name_, resolve_lcm_url(lcm_url_), config.section<BusParams>("bus"));
    // What this process runs with, once, so that a log of the run replays with it (gpilot-replay).
    config_t c{};
    c.utime = node.now();
    c.process = name_;
    c.pid = static_cast<int32_t>(getpid());
    c.yaml = effective_config_yaml(config);
    node.publish_report("CONFIG", c);
    return body(config, node);
  });
}

}  // namespace gpilot
