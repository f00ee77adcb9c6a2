// Wires the decide stage to a bus (see decide_service.cpp). The returned object holds the stage's state;
// keep it alive while the bus runs.
#pragma once

#include <memory>

#include "bus_node.hpp"
#include "config.hpp"

namespace gpilot {

std::shared_ptr<void> start_decide_service(const Config& config, BusNode& node);

}  // namespace gpilot
