// The sections of the config file and the Params struct that reads each. Every process validates the
// whole file at start, so a typo anywhere stops it before it touches the bus.
#pragma once

#include <string>

#include "config.hpp"

namespace gpilot {

// Reads every section; throws ConfigError naming the first bad key, value or unknown section.
void validate_config(const Config& config);

// deploy/config/default.yaml: every section and key at its default, with a comment.
std::string default_config_yaml();

// The same for the values config gives (what a process runs with: published on CONFIG at its start, and
// read back by gpilot-replay with Config::from_string).
std::string effective_config_yaml(const Config& config);

}  // namespace gpilot
