// What gpilot-hands reads and writes, declared once (common/channel.hpp): its adapter, gpilot-replay, the
// view, gpilot-health --channels and DEVELOPERS.md's table read these.
#pragma once

#include "channel.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/user_track_t.hpp"

namespace gpilot {
namespace hands_channels {

constexpr Channel<image_t> kCamera{"CAMERA"};
constexpr Channel<user_track_t> kUserTrack{"USER_TRACK"};  //!< paired with CAMERA by seq
constexpr Channel<hand_obs_t> kHandObs{"HAND_OBS"};

constexpr ChannelUse kUses[] = {kCamera.in(), kUserTrack.in(), kHandObs.out()};

}  // namespace hands_channels
}  // namespace gpilot
