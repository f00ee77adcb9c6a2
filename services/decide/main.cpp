// gpilot-decide: reads HAND_OBS, runs the state buffers and Alg. 3, writes GESTURE_CMD (one per HAND_OBS,
// with that frame's seq and utime). Also HEALTH.
#include "decide_service.hpp"
#include "service_cli.hpp"

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-decide",
                 "gpilot-decide: the paper's Alg. 3. Keeps the last N hand observations in S_out and S_front and\n"
                 "publishes one GESTURE_CMD per HAND_OBS (mode, camera-frame direction, buffer counts).\n"
                 "Reads HAND_OBS; writes GESTURE_CMD, HEALTH. Config section: decide.");
  return cli.run_node(argc, argv, [](const Config& config, BusNode& node) {
    const auto stage = start_decide_service(config, node);
    node.run();
    return 0;
  });
}
