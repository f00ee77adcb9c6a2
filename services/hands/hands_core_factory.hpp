// The one place the hands stage's core is built from its config (hands.method): the service, gpilot-replay,
// the eval tools, the fuzz target and the tests all take their method from here.
#pragma once

#include <memory>

#include "hands/hand_method.hpp"
#include "hands/hands_params.hpp"

namespace gpilot {

// The method hands.method names, with its models loaded (relative paths from the project root). Throws
// SkinModelError (skin: a missing or malformed table), PoseModelError (pose: a model file missing, truncated or
// of the wrong shape) or ConfigError (a method this build does not have).
std::unique_ptr<HandMethod> make_hand_method(const HandsParams& params);

}  // namespace gpilot
