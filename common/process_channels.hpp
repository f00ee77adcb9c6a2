// The channels every gpilot process writes, whatever its stage (see channel.hpp).
#pragma once

#include "channel.hpp"
#include "gpilot/config_t.hpp"
#include "gpilot/health_t.hpp"

namespace gpilot {
namespace process_channels {

constexpr Channel<health_t> kHealth{"HEALTH"};  //!< once a second (BusNode::publish_health); gpilot-health reads it
constexpr Channel<config_t> kConfig{"CONFIG"};  //!< once at start, the effective config (ServiceCli); gpilot-replay reads it

constexpr ChannelUse kUses[] = {kHealth.out(), kConfig.out()};

}  // namespace process_channels
}  // namespace gpilot
