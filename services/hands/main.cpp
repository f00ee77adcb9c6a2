// gpilot-hands: the hands stage as an LCM service.
// Reads CAMERA (gpilot.image_t, BGR8 or JPEG) and USER_TRACK (gpilot.user_track_t), pairs them by seq,
// and writes HAND_OBS (gpilot.hand_obs_t) for each pair: a stretched-out hand (vector from the shoulder centre),
// a hand in front of the body (vector from the body centre) or NONE, read from the user's body landmarks
// (hands.method pose) or by the paper's Alg. 1/2 on skin colour (skin). Its models are loaded before the bus
// starts: a missing or broken model file stops it as a bad config does.
// A frame or track that never meets its partner is dropped and counted (HEALTH rejected); a track that
// is not TRACKING gives NONE.
#include "hands/hands_core_factory.hpp"
#include "hands/hands_service.hpp"
#include "service_cli.hpp"
#include "system/opencv_threads.hpp"

using namespace gpilot;

int main(int argc, char** argv) {
  ServiceCli cli("gpilot-hands",
                 "Hands stage: CAMERA + USER_TRACK (paired by seq) -> HAND_OBS.\n"
                 "hands.method skin (default): the paper's Alg. 1/2 on a skin table in a rectangle around the user box.\n"
                 "hands.method pose: the user's body landmarks (BlazePose, seeded by the tracker's box); an arm stretched\n"
                 "out (vector from the shoulder centre) or a hand in front of the body (vector from the body centre).\n"
                 "Parameters: section `hands` of the config.");
  std::unique_ptr<HandMethod> method;
  cli.before_bus([&](const Config& config) {
    set_opencv_threads(opencv_threads_of(config, "hands"));
    method = make_hand_method(config.section<HandsParams>("hands"));
  });
  return cli.run_node(argc, argv, [&](const Config& config, BusNode& node) {
    const auto stage = start_hands_service(config, node, std::move(method));
    node.run();
    return 0;
  });
}
