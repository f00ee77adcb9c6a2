// gpilot-flight: the only process that moves the vehicle (the stage itself: flight_service.cpp, which
// gpilot-replay runs too). Reads GESTURE_CMD, USER_TRACK, FLIGHT_CONTROL (and VEHICLE_STATE with backend none);
// writes FLIGHT_SETPOINT, VEHICLE_STATE, AUTOPILOT (backend mavlink), HEALTH.
// Watched: READY=1 once running and WATCHDOG=1 from the loop that publishes the setpoints (sd_notify; systemd's
// WatchdogSec or gpilot-launch's watchdog_s), so a frozen loop is a silent watchdog: killed and restarted.
#include "flight_service.hpp"
#include "service_cli.hpp"

#include <systemd/sd-daemon.h>

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-flight",
                 "gpilot-flight: turns GESTURE_CMD into a body-frame velocity setpoint (speed from the hand's offset\n"
                 "in user-box widths, yaw to keep the user centred, the paper's 600 ms command spacing) and hovers\n"
                 "unless ENGAGED with fresh, valid inputs and a tracked user. Backends (flight.backend): sim (built-in\n"
                 "quadrotor, publishes VEHICLE_STATE), mavlink (MAVLink v2 over UDP, mavlink.endpoint), none.\n"
                 "Reads GESTURE_CMD, USER_TRACK, FLIGHT_CONTROL (+ VEHICLE_STATE with backend none); writes\n"
                 "FLIGHT_SETPOINT, VEHICLE_STATE, AUTOPILOT (what the autopilot said: HEARTBEAT, PARAM_VALUE), HEALTH.\n"
                 "Config sections: flight, sim, mavlink.");
  return cli.run_node(argc, argv, [](const Config& config, BusNode& node) {
    const auto stage = start_flight_service(config, node);
    // The watchdog: its period comes from the supervisor (WATCHDOG_USEC); pinged at a quarter of it by a timer of
    // this loop (not a thread of its own, and not tied to setpoint_rate_hz, which may be slower than the deadline):
    // a loop that stops, stops the pings.
    uint64_t watchdog_usec = 0;
    if (sd_watchdog_enabled(0, &watchdog_usec) > 0)
      node.every(static_cast<double>(watchdog_usec) * 1e-6 / 4, [] { sd_notify(0, "WATCHDOG=1"); });
    sd_notify(0, "READY=1");
    node.run();
    // On its way out, not frozen (the supervisor waits instead of killing).
    sd_notify(0, "STOPPING=1");
    return 0;
  });
}
