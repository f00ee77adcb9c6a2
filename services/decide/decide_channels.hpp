// What gpilot-decide reads and writes, declared once (common/channel.hpp): its adapter, gpilot-replay, the
// view, gpilot-health --channels and DEVELOPERS.md's table read these.
#pragma once

#include "channel.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/hand_obs_t.hpp"

namespace gpilot {
namespace decide_channels {

constexpr Channel<hand_obs_t> kHandObs{"HAND_OBS"};
constexpr Channel<gesture_cmd_t> kGestureCmd{"GESTURE_CMD"};

constexpr ChannelUse kUses[] = {kHandObs.in(), kGestureCmd.out()};

}  // namespace decide_channels
}  // namespace gpilot
