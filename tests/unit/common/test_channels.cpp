// Channels are declared once per user (common/channel.hpp): the declarations agree with each other, the
// adapters subscribe and publish only through them, and DEVELOPERS.md's channel table is theirs.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>

#include "system/system_channels.hpp"
#include "text_file.hpp"

namespace gpilot {
namespace {

using test::read_text_file;

TEST(Channels, EveryDeclarationOfANameHasOneTypeAndEveryReadChannelIsWritten) {
  EXPECT_EQ(channel_declaration_errors(system_channels()), std::vector<std::string>{});
}

TEST(Channels, TwoTypesForOneNameAndAChannelNobodyWritesAreFound) {
  // GIVEN a producer and two consumers, one with CAMERA of another type, one reading a channel nobody writes
  constexpr Channel<image_t> camera{"CAMERA"};
  constexpr Channel<user_track_t> wrong_camera{"CAMERA"};
  constexpr Channel<hand_obs_t> orphan{"HAND_OBS_TYPO"};
  const std::vector<ChannelUser> users = {{"producer", {camera.out()}},
                                          {"consumer", {wrong_camera.in()}},
                                          {"reader", {camera.in(), orphan.in()}}};
  // THEN both are named
  EXPECT_EQ(channel_declaration_errors(users),
            (std::vector<std::string>{"CAMERA: producer declares image_t, consumer user_track_t",
                                      "CAMERA: consumer declares user_track_t, reader image_t",
                                      "HAND_OBS_TYPO: reader reads it, nobody writes it"}));
}

TEST(Channels, TheStagesDeclareThePipelinesChannels) {
  // The names logs, lcm-spy and the tests depend on (ARCHITECTURE.md), each with its type.
  const std::string table = channel_table_markdown();
  for (const char* row : {"| CAMERA | image_t | gpilot-capture | gpilot-tracker, gpilot-hands |",
                          "| USER_TRACK | user_track_t | gpilot-tracker | gpilot-hands, gpilot-flight, gpilot-launch |",
                          "| HAND_OBS | hand_obs_t | gpilot-hands | gpilot-decide |",
                          "| GESTURE_CMD | gesture_cmd_t | gpilot-decide | gpilot-flight, gpilot-launch |",
                          "| FLIGHT_SETPOINT | flight_setpoint_t | gpilot-flight | - |",
                          "| FLIGHT_CONTROL | flight_control_t | gpilot-view, gpilot-ctl, gpilot-launch | gpilot-flight |",
                          "| HEALTH | health_t | every process | gpilot-launch, gpilot-health |"})
    EXPECT_NE(table.find(row), std::string::npos) << row << "\nin\n" << table;
}

// An adapter or tool names a channel only through a declaration: a string literal given to subscribe or
// publish is a channel nobody declared (and that replay, the view and the docs do not know).
TEST(Channels, NoAdapterOrToolSubscribesOrPublishesALiteralChannel) {
  const std::regex literal(R"((subscribe(<[^>]*>)?|subscribe_taking(<[^>]*>)?|subscribe_raw|publish|publish_report|publish_raw)\(\s*")");
  std::vector<std::string> found;
  for (const char* dir : {"services", "tools"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(std::string(GPILOT_SOURCE_DIR) + "/" + dir)) {
      if (e.path().extension() != ".cpp" && e.path().extension() != ".hpp") continue;
      const std::string rel = std::filesystem::relative(e.path(), GPILOT_SOURCE_DIR).string();
      std::istringstream lines(read_text_file(e.path()));
      int n = 0;
      for (std::string line; std::getline(lines, line);) {
        ++n;
        if (std::regex_search(line, literal))
          found.push_back(rel + ":" + std::to_string(n));
      }
    }
  EXPECT_EQ(found, std::vector<std::string>{}) << "use the stage's <stage>_channels.hpp constants";
}

// DEVELOPERS.md's table is the declarations' (regenerate: build/bin/gpilot-health --channels).
TEST(Channels, DevelopersTableIsTheDeclarations) {
  const std::string doc = read_text_file(std::string(GPILOT_SOURCE_DIR) + "/DEVELOPERS.md");
  const std::string begin = "<!-- channels: build/bin/gpilot-health --channels -->\n";
  const std::string end = "<!-- end of channels -->";
  const auto b = doc.find(begin);
  const auto e = doc.find(end);
  ASSERT_NE(b, std::string::npos) << "DEVELOPERS.md has no channel table";
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), channel_table_markdown())
      << "regenerate the table in DEVELOPERS.md with build/bin/gpilot-health --channels";
}

}  // namespace
}  // namespace gpilot
