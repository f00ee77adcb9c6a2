// The one list of the config file's sections, in the order of deploy/config/default.yaml: common's own
// (bus, image) and each stage's, declared by the stage next to its Params.
#include "bus_params.hpp"
#include "capture/capture_params.hpp"
#include "config_schema.hpp"
#include "decide/decide_params.hpp"
#include "flight/flight_params.hpp"
#include "hands/hands_params.hpp"
#include "image_codec_params.hpp"
#include "tracker/tracker_params.hpp"

namespace gpilot {

const ConfigSchema& config_schema() {
  static const ConfigSchema schema = [] {
    ConfigSchema s;
    s.section<BusParams>("bus");
    add_capture_sections(s);
    add_tracker_sections(s);
    add_hands_sections(s);
    add_decide_sections(s);
    add_flight_sections(s);
    s.section<ImageLimits>("image");
    return s;
  }();
  return schema;
}

void validate_config(const Config& config) { config_schema().validate(config); }

std::string default_config_yaml() { return config_schema().defaults_yaml(); }

std::string effective_config_yaml(const Config& config) { return config_schema().effective_yaml(config); }

}  // namespace gpilot
