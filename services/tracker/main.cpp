// gpilot-tracker: finds the user and keeps a body box on them.
// Reads CAMERA (image_t) and TRACKER_INIT (tracker_init_t); writes USER_TRACK (user_track_t, one per
// accepted frame, with that frame's seq and utime) and HEALTH. A frame that does not decode or that the
// tracker cannot use is rejected (counted in HEALTH) and does not advance the track.
#include <memory>

#include "face_cascade.hpp"
#include "service_cli.hpp"
#include "system/opencv_threads.hpp"
#include "tracker_service.hpp"

int main(int argc, char** argv) {
  gpilot::ServiceCli cli("gpilot-tracker",
                         "Haar face search, body box by head-body ratio, DSST tracking with PSR confidence;\n"
                         "with tracker.person.enabled, BlazePose's person detector finds the user without a face too.\n"
                         "CAMERA + TRACKER_INIT in, USER_TRACK out.");
  // The cascade and the person detector's model are loaded before the bus starts: a missing file is named, status 2.
  std::unique_ptr<gpilot::UserTracker> tracker;
  cli.before_bus([&](const gpilot::Config& config) {
    const auto params = config.section<gpilot::TrackerParams>("tracker");
    tracker = std::make_unique<gpilot::UserTracker>(params, gpilot::load_tracker_models(params));
  });
  return cli.run_node(argc, argv, [&](const gpilot::Config& config, gpilot::BusNode& node) {
    gpilot::set_opencv_threads(gpilot::opencv_threads_of(config, "tracker"));
    const auto stage = gpilot::start_tracker_service(config, node, std::move(tracker));
    node.run();
    return 0;
  });
}
