#include "hands_core_factory.hpp"

#include "config.hpp"
#include "hands/pose_hand_method.hpp"
#include "hands/skin_hand_method.hpp"
#include "hands/skin_model.hpp"
#include "paths.hpp"

namespace gpilot {

std::unique_ptr<HandMethod> make_hand_method(const HandsParams& params) {
  if (params.method == "skin") {
    const std::string model_path = resolve_project_path(params.skin.model);
    return std::make_unique<SkinHandMethod>(params, SkinModel::load(model_path), model_path);
  }
  if (params.method == "pose") return std::make_unique<PoseHandMethod>(params, PoseModels::load(params.pose));
  throw ConfigError("hands.method: '" + params.method + "' is not a method this build has (pose, skin)");
}

}  // namespace gpilot
