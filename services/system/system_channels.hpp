// Every channel of the system, from the declarations of its users: each stage's own
// (services/<stage>/<stage>_channels.hpp), every process's (common/process_channels.hpp) and the operator's
// and monitors' tools. Read by the consistency test (tests/unit/common/test_channels.cpp), gpilot-health
// --channels and DEVELOPERS.md's channel table, which a test compares with channel_table_markdown().
#pragma once

#include <iterator>
#include <string>
#include <vector>

#include "capture/capture_channels.hpp"
#include "decide/decide_channels.hpp"
#include "flight/flight_channels.hpp"
#include "hands/hands_channels.hpp"
#include "process_channels.hpp"
#include "tracker/tracker_channels.hpp"

namespace gpilot {

// Who uses channels (a process, or a group of tools), and how.
struct ChannelUser {
  std::string name;
  std::vector<ChannelUse> uses;
};

template <size_t N>
std::vector<ChannelUse> channel_uses(const ChannelUse (&uses)[N]) {
  return {std::begin(uses), std::end(uses)};
}

// The stages in pipeline order, then the tools and every process.
inline std::vector<ChannelUser> system_channels() {
  return {
      {"gpilot-capture", channel_uses(capture_channels::kUses)},
      {"gpilot-tracker", channel_uses(tracker_channels::kUses)},
      {"gpilot-hands", channel_uses(hands_channels::kUses)},
      {"gpilot-decide", channel_uses(decide_channels::kUses)},
      {"gpilot-flight", channel_uses(flight_channels::kUses)},
      // The operator's tools (declared here: services/ does not include tools/). gpilot-view's live window
      // also reads every channel it draws; gpilot-replay replays a stage with the CONFIG it logged.
      {"gpilot-view", {tracker_channels::kTrackerInit.out(), flight_channels::kFlightControl.out()}},
      {"gpilot-ctl", {flight_channels::kFlightControl.out()}},
      {"gpilot-launch",
       {flight_channels::kFlightControl.out(), process_channels::kHealth.in(), flight_channels::kGestureCmd.in(),
        flight_channels::kUserTrack.in()}},
      {"gpilot-health", {process_channels::kHealth.in()}},
      {"gpilot-replay", {process_channels::kConfig.in()}},
      {"every process", channel_uses(process_channels::kUses)},
  };
}

// What is wrong with a set of declarations, one line each: a name declared with two message types, a
// channel read that nobody writes. Empty for the system's (a test).
inline std::vector<std::string> channel_declaration_errors(const std::vector<ChannelUser>& users) {
  struct Decl {
    const std::string* user;
    ChannelUse use;
  };
  std::vector<Decl> all;
  for (const auto& user : users)
    for (const auto& use : user.uses) all.push_back({&user.name, use});
  std::vector<std::string> errors;
  for (size_t i = 0; i < all.size(); ++i) {
    const Decl& a = all[i];
    bool written = false;
    for (size_t j = 0; j < all.size(); ++j) {
      const Decl& b = all[j];
      if (std::string(a.use.name) != b.use.name) continue;
      written = written || b.use.role == ChannelRole::Out;
      if (j > i && a.use.type() != b.use.type())
        errors.push_back(std::string(a.use.name) + ": " + *a.user + " declares " + a.use.type() + ", " + *b.user +
                         " " + b.use.type());
    }
    if (a.use.role == ChannelRole::In && !written)
      errors.push_back(std::string(a.use.name) + ": " + *a.user + " reads it, nobody writes it");
  }
  return errors;
}

// | channel | type | written by | read by |, one row per channel: those written, in the order of their
// writers above (the pipeline's), then any only read.
inline std::string channel_table_markdown() {
  struct Row {
    std::string name, type, writers, readers;
  };
  std::vector<Row> rows;
  const auto users = system_channels();
  for (const ChannelRole pass : {ChannelRole::Out, ChannelRole::In})
    for (const auto& user : users)
      for (const auto& use : user.uses) {
        if (use.role != pass) continue;
        Row* row = nullptr;
        for (auto& r : rows)
          if (r.name == use.name) row = &r;
        if (!row) row = &rows.emplace_back(Row{use.name, use.type(), "", ""});
        std::string& list = use.role == ChannelRole::Out ? row->writers : row->readers;
        list += (list.empty() ? "" : ", ") + user.name;
      }
  std::string out = "| channel | type | written by | read by |\n|---|---|---|---|\n";
  for (const auto& r : rows)
    out += "| " + r.name + " | " + r.type + " | " + r.writers + " | " + (r.readers.empty() ? "-" : r.readers) + " |\n";
  return out;
}

}  // namespace gpilot
