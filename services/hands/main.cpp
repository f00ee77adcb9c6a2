// gpilot-hands: the hands stage as an LCM service.
// Reads CAMERA (gpilot.image_t, BGR8 or JPEG) and USER_TRACK (gpilot.user_track_t), pairs them by seq,
// and writes HAND_OBS (gpilot.hand_obs_t) for each pair: the paper's Alg. 1 (stretched-out hand, vector
// from the shoulder centre) else Alg. 2 (hand in front of the body, vector from the body centre) else NONE.
// A frame or track that never meets its partner is dropped and counted (HEALTH rejected); a track that
// is not TRACKING gives NONE.
#include "hands/hands_service.hpp"
#include "service_cli.hpp"

using namespace gpilot;

int main(int argc, char** argv) {
  ServiceCli cli("gpilot-hands",
                 "Hands stage: CAMERA + USER_TRACK (paired by seq) -> HAND_OBS.\n"
                 "Skin by histogram lookup in a rectangle extended from the user box (face/neck and legs removed),\n"
                 "then the paper's Alg. 1 (stretched-out hand, vector from the shoulder centre) or Alg. 2 (hand in front\n"
                 "of the body, vector from the body centre). Parameters: section `hands` of the config.");
  return cli.run_node(argc, argv, [&](const Config& config, BusNode& node) {
    const auto stage = start_hands_service(config, node);
    node.run();
    return 0;
  });
}
