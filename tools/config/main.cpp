// gpilot-config: prints the default config (deploy/config/default.yaml) or checks a config file.
#include <cstdio>

#include "config_schema.hpp"
#include "service_cli.hpp"

int main(int argc, char** argv) {
  gpilot::ServiceCli cli("gpilot-config", "Print the default configuration, or check one (--config FILE [--set ...]).");
  bool defaults = false;
  cli.app().add_flag("--defaults", defaults, "print every section and key at its default, with comments");
  return cli.run(argc, argv, [&](const gpilot::Config& config) {
    if (defaults) {
      std::fputs(gpilot::default_config_yaml().c_str(), stdout);
    } else {
      std::printf("%s: ok (%zu sections)\n", config.origin().c_str(), config.section_names().size());
    }
    return 0;
  });
}
