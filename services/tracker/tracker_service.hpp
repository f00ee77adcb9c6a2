// Wires the tracker stage to a bus (see tracker_service.cpp). The returned object holds the stage's
// state; keep it alive while the bus runs.
#pragma once

#include <memory>

#include "bus_node.hpp"
#include "config.hpp"

namespace gpilot {

std::shared_ptr<void> start_tracker_service(const Config& config, BusNode& node);

}  // namespace gpilot
