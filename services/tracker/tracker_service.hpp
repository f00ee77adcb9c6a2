// Wires the tracker stage to a bus (see tracker_service.cpp). The returned object holds the stage's
// state; keep it alive while the bus runs.
#pragma once

#include <memory>

#include "bus_node.hpp"
#include "config.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "user_tracker.hpp"

namespace gpilot {

std::shared_ptr<void> start_tracker_service(const Config& config, BusNode& node);
// ... with a tracker built before the bus started (gpilot-tracker: the face cascade and, with tracker.person, the
// person detector's model loaded by ServiceCli::before_bus, so a missing file stops it as a bad config does).
std::shared_ptr<void> start_tracker_service(const Config& config, BusNode& node, std::unique_ptr<UserTracker> tracker);

// The core's output for a frame as gpilot-tracker publishes it on USER_TRACK (utime, seq and size from the
// frame's message; its pixels are not read). Also the tracker fuzz target, which checks it.
user_track_t to_message(const TrackOutput& t, const image_t& frame);

}  // namespace gpilot
