// gpilot-ctl: the operator's switch. Publishes one FLIGHT_CONTROL request (engage, disengage, arm, takeoff,
// land, disarm) for gpilot-flight, the only process that moves the vehicle.
#include <cstdio>
#include <map>
#include <string>

#include "bus_node.hpp"
#include "flight/flight_channels.hpp"
#include "log.hpp"
#include "service_cli.hpp"

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-ctl",
                 "gpilot-ctl: sends one operator request to gpilot-flight on FLIGHT_CONTROL.\n"
                 "  engage     follow gesture commands      disengage  hover, ignore gestures\n"
                 "  arm        arm the motors               takeoff    climb to --altitude metres\n"
                 "  land       disengage and land           disarm     stop the motors (on the ground)");
  std::string command;
  float altitude = 1.5f;
  int repeat = 3;
  cli.app().add_option("command", command, "engage | disengage | arm | takeoff | land | disarm")->required();
  cli.app().add_option("--altitude", altitude, "takeoff altitude above the take-off point, m (default 1.5)");
  cli.app().add_option("--repeat", repeat,
                       "send the request this many times, 50 ms apart (UDP multicast may drop one; default 3)");
  return cli.run_node(argc, argv, [&](const Config&, BusNode& node) {
    static const std::map<std::string, int8_t> kCommands = {
        {"engage", flight_control_t::COMMAND_ENGAGE}, {"disengage", flight_control_t::COMMAND_DISENGAGE},
        {"arm", flight_control_t::COMMAND_ARM},       {"takeoff", flight_control_t::COMMAND_TAKEOFF},
        {"land", flight_control_t::COMMAND_LAND},     {"disarm", flight_control_t::COMMAND_DISARM}};
    const auto it = kCommands.find(command);
    if (it == kCommands.end()) {
      log_error("unknown command '%s' (engage|disengage|arm|takeoff|land|disarm)", command.c_str());
      return 2;
    }
    if (it->second == flight_control_t::COMMAND_TAKEOFF && !(altitude > 0.0f)) {
      log_error("--altitude must be positive");
      return 2;
    }
    flight_control_t m{};
    m.utime = node.now();
    m.seq = 0;
    m.command = it->second;
    m.takeoff_altitude = it->second == flight_control_t::COMMAND_TAKEOFF ? altitude : 0.0f;
    m.source = "gpilot-ctl";
    // The same request repeated is harmless: each one sets the same state. The copies are byte-identical
    // messages (same utime and seq): a receiver acts on the first and its bus drops the rest as duplicates.
    Pacer pace(20.0);
    for (int i = 0; i < std::max(1, repeat); ++i) {
      if (i) pace.wait();
      publish(node, flight_channels::kFlightControl, m);
    }
    std::printf("gpilot-ctl: sent %s\n", command.c_str());
    return 0;
  });
}
