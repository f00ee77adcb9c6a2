// What gpilot-capture reads and writes, declared once (common/channel.hpp): its adapter, gpilot-replay, the
// view, gpilot-health --channels and DEVELOPERS.md's table read these.
#pragma once

#include "channel.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/vehicle_state_t.hpp"

namespace gpilot {
namespace capture_channels {

constexpr Channel<vehicle_state_t> kVehicleState{"VEHICLE_STATE"};  //!< the synthetic camera flies with it
constexpr Channel<image_t> kCamera{"CAMERA"};
constexpr Channel<ground_truth_t> kGroundTruth{"GROUND_TRUTH"};  //!< the synthetic world's, per frame

constexpr ChannelUse kUses[] = {kVehicleState.in(), kCamera.out(), kGroundTruth.out()};

}  // namespace capture_channels
}  // namespace gpilot
