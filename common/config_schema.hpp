// The sections of the config file and the Params struct that reads each. Every process validates the
// whole file at start, so a typo anywhere stops it before it touches the bus.
//
// common/ knows no stage: a stage declares its sections next to its Params (add_<stage>_sections in
// services/<stage>/<stage>_params.hpp), and the schema of the whole file is assembled from them by an
// explicit list of calls in services/system/config_sections.cpp (library gpilot_sections, which
// gpilot_common links for ServiceCli). No static registration: a registrar in a static library that nothing
// references is dropped by the linker, and a section would silently go missing.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "config.hpp"

namespace gpilot {

class ConfigSchema {
 public:
  // Adds section `name`, read by Params type P (its visit(), defaults and check()). A name added twice is a
  // programming error (std::logic_error), not a config error.
  template <class P>
  ConfigSchema& section(const std::string& name) {
    add(name, [name](const Config& config) { (void)config.section<P>(name.c_str()); },
        [name](const Config* config) {
          P params = config ? config->section<P>(name.c_str()) : P{};
          ParamWriter w(2);
          params.visit(w);
          return w.str();
        });
    return *this;
  }

  // Adds a rule between sections (a section's own rules are its Params::check()); it throws ConfigError
  // naming the key. Rules run after every section has been read, in the order added.
  ConfigSchema& rule(std::function<void(const Config&)> across);

  // Reads every section; throws ConfigError naming the first bad key, value or unknown section.
  void validate(const Config& config) const;
  // Every section and key at its default, with a comment (the form of deploy/config/default.yaml).
  std::string defaults_yaml() const;
  // The same for the values config gives.
  std::string effective_yaml(const Config& config) const;

  std::vector<std::string> section_names() const;

 private:
  struct Section {
    std::string name;
    std::function<void(const Config&)> read;
    std::function<std::string(const Config*)> write;  // nullptr: the defaults
  };
  void add(const std::string& name, std::function<void(const Config&)> read,
           std::function<std::string(const Config*)> write);
  std::string write_all(const Config* config) const;

  std::vector<Section> sections_;
  std::vector<std::function<void(const Config&)>> rules_;
};

// The whole file's schema, every stage's sections in the order of deploy/config/default.yaml. Declared here
// so that ServiceCli (common/) can validate without knowing a stage; defined in
// services/system/config_sections.cpp (gpilot_sections), the one place that lists the stages.
const ConfigSchema& config_schema();

// Shorthands on config_schema() (also defined by gpilot_sections).
// Reads every section; throws ConfigError naming the first bad key, value or unknown section.
void validate_config(const Config& config);

// deploy/config/default.yaml: every section and key at its default, with a comment.
std::string default_config_yaml();

// The same for the values config gives (what a process runs with: published on CONFIG at its start, and
// read back by gpilot-replay with Config::from_string).
std::string effective_config_yaml(const Config& config);

}  // namespace gpilot
