// Wires the decide stage to a bus (see decide_service.cpp). The returned object holds the stage's state;
// keep it alive while the bus runs.
#pragma once

#include <memory>

#include "bus_node.hpp"
#include "config.hpp"
#include "gesture_decider.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/hand_obs_t.hpp"

namespace gpilot {

// HAND_OBS as the core reads it (also gpilot-eval-decide, which runs the core over logs without a bus).
HandObservation to_hand_observation(const hand_obs_t& m);
// A command as gpilot-decide publishes it on GESTURE_CMD (also the decide fuzz target, which checks it).
gesture_cmd_t to_message(const GestureCommand& c);

std::shared_ptr<void> start_decide_service(const Config& config, BusNode& node);

}  // namespace gpilot
