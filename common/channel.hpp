// A channel is declared once, by the stage that uses it, with its message type: services/<stage>/<stage>_channels.hpp
// names what the stage reads and writes (a Channel<Msg> constant each, and kUses, the list with the role).
// Its adapter subscribes and publishes through the constants (subscribe/publish below check the message type
// at compile time); gpilot-replay's table, gpilot-view, gpilot-health --channels and DEVELOPERS.md's channel
// table read the same declarations. A channel two stages use is declared by each (the producer writes it,
// the consumer reads it): tests/unit/common/test_channels.cpp checks that every declaration of a name has
// the same type and that what a stage reads is written by a stage or an operator tool.
//
// No LCM here (only the name and the message type's name): the helpers take the bus node as a template
// parameter, so this header does not pull the bus into whoever includes it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

namespace gpilot {

enum class ChannelRole { In, Out };

// One use of a channel by a stage: its name, its message type's LCM name ("image_t") and whether the stage
// reads or writes it.
struct ChannelUse {
  const char* name;
  const char* (*type_name)();
  ChannelRole role;

  std::string type() const { return type_name(); }
};

template <class Msg>
struct Channel {
  using Message = Msg;
  const char* name;

  constexpr ChannelUse in() const { return {name, &Msg::getTypeName, ChannelRole::In}; }
  constexpr ChannelUse out() const { return {name, &Msg::getTypeName, ChannelRole::Out}; }
  operator std::string() const { return name; }  // for APIs that take a channel's name
};

// node.subscribe on a declared channel: the handler takes the channel's message type.
template <class Node, class Msg, class Handler>
void subscribe(Node& node, const Channel<Msg>& channel, Handler&& handler, int queue_capacity = 0) {
  node.template subscribe<Msg>(channel.name, std::function<void(const Msg&, int64_t)>(std::forward<Handler>(handler)),
                               queue_capacity);
}

// node.subscribe_taking on a declared channel: the handler takes the channel's message type, non-const (it
// may move or swap the message's contents out: BusNode::subscribe_taking).
template <class Node, class Msg, class Handler>
void subscribe_taking(Node& node, const Channel<Msg>& channel, Handler&& handler, int queue_capacity = 0) {
  node.template subscribe_taking<Msg>(channel.name, std::function<void(Msg&, int64_t)>(std::forward<Handler>(handler)),
                                      queue_capacity);
}

// node.publish on a declared channel: a message of another type does not compile.
template <class Node, class Msg>
void publish(Node& node, const Channel<Msg>& channel, const Msg& msg) {
  node.publish(channel.name, msg);
}

}  // namespace gpilot
