// Wires the flight stage to a bus (see flight_service.cpp): gpilot-flight (live LCM) and gpilot-replay --stage
// flight (a log through memq://, on the log's clock) run this same code. The returned object holds the stage's
// state; keep it alive while the bus runs.
#pragma once

#include <memory>

#include "bus_node.hpp"
#include "config.hpp"

namespace gpilot {

// Where the vehicle is: Own, the backend's (the simulator, or the autopilot over MAVLink, whose VEHICLE_STATE and
// AUTOPILOT messages the stage publishes and takes); FromBus, the bus's (a replay: the log's VEHICLE_STATE and
// AUTOPILOT are read, nothing is simulated or sent; with backend mavlink the engage gate and the link watch
// decide from the logged AUTOPILOT as they did live).
enum class VehicleSource { Own, FromBus };

// GESTURE_CMD, USER_TRACK, FLIGHT_CONTROL (and VEHICLE_STATE with flight.backend none) in; FLIGHT_SETPOINT
// every 1 / flight.setpoint_rate_hz on the node's timer, VEHICLE_STATE from the simulator (sim) or the
// autopilot (mavlink), AUTOPILOT (mavlink). Every time it reads is the node's clock (BusNode::now), so a replay
// on the log's clock decides as the live run did. Throws ConfigError for a MAVLink signing key it cannot read.
std::shared_ptr<void> start_flight_service(const Config& config, BusNode& node,
                                           VehicleSource vehicle = VehicleSource::Own);

}  // namespace gpilot
