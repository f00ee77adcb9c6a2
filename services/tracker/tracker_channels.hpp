// What gpilot-tracker reads and writes, declared once (common/channel.hpp): its adapter, gpilot-replay, the
// view, gpilot-health --channels and DEVELOPERS.md's table read these.
#pragma once

#include "channel.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "gpilot/user_track_t.hpp"

namespace gpilot {
namespace tracker_channels {

constexpr Channel<image_t> kCamera{"CAMERA"};
constexpr Channel<tracker_init_t> kTrackerInit{"TRACKER_INIT"};  //!< from an operator (gpilot-view, gpilot-ctl)
constexpr Channel<user_track_t> kUserTrack{"USER_TRACK"};

constexpr ChannelUse kUses[] = {kCamera.in(), kTrackerInit.in(), kUserTrack.out()};

}  // namespace tracker_channels
}  // namespace gpilot
