// gpilot-config: prints the default config (deploy/config/default.yaml) or checks a config file.
#include <cstdio>

#include "bus_node.hpp"
#include "config_schema.hpp"
#include "service_cli.hpp"

int main(int argc, char** argv) {
  gpilot::ServiceCli cli("gpilot-config", "Print the default configuration, or check one (--config FILE [--set ...]).");
  bool defaults = false;
  cli.app().add_flag("--defaults", defaults, "print every section and key at its default, with comments");
  bool frames_url = false;
  cli.app().add_flag("--frames-url", frames_url,
                     "print the URL the frames travel on with this config and bus URL (bus.frames_url, else the bus\n"
                     "URL's group with port + 1): for lcm-logger, lcm-spy (deploy/spy) and scripts");
  return cli.run(argc, argv, [&](const gpilot::Config& config) {
    if (frames_url) {
      std::printf("%s\n", gpilot::frames_url_for(gpilot::resolve_lcm_url(cli.lcm_url()),
                                                 config.section<gpilot::BusParams>("bus")).c_str());
    } else if (defaults) {
      std::fputs(gpilot::default_config_yaml().c_str(), stdout);
    } else {
      std::printf("%s: ok (%zu sections)\n", config.origin().c_str(), config.section_names().size());
    }
    return 0;
  });
}
