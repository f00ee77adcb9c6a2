// Fuzz target: the config reader. The input's first line is a --set assignment, the rest a YAML file; both
// go through Config and every section's Params (validate_config, as each service does before its bus
// starts). A bad file is a ConfigError with the key named, never another exception or a crash.
#include <cstdint>
#include <string>

#include "config.hpp"
#include "config_schema.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t nl = text.find('\n');
  const std::string assignment = nl == std::string::npos ? std::string() : text.substr(0, nl);
  const std::string yaml = nl == std::string::npos ? text : text.substr(nl + 1);
  try {
    gpilot::Config config = gpilot::Config::from_string(yaml, "fuzz");
    if (!assignment.empty()) config.set(assignment);
    gpilot::validate_config(config);
    (void)gpilot::default_config_yaml();
  } catch (const gpilot::ConfigError&) {
    // the expected verdict on a bad file
  } catch (const std::exception& e) {
    gpilot::fuzz::fail(std::string("the config reader let an exception other than ConfigError out: ") + e.what());
  }
  return 0;
}
