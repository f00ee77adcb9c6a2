// deploy/services.yaml: parsing, ${var} substitution, and the systemd units made from it.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <sstream>

#include "service_set.hpp"

namespace gpilot {
namespace {

TEST(ServiceSet, SubstitutesVariablesAndDropsEmptyWords) {
  const std::string yaml = R"(
services:
  - name: a
    command: [gpilot-a, --config, "${config}", "${extra}"]
    stop_signal: INT
    stop_timeout_s: 5
    ends_run: true
  - name: b
    command: [/usr/bin/b]
    respawn: false
    only_if: [log]
)";
  const auto s = parse_service_set(yaml, {{"config", "c.yaml"}, {"extra", ""}, {"log", "x"}});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].command, (std::vector<std::string>{"gpilot-a", "--config", "c.yaml"}));
  EXPECT_EQ(s[0].stop_signal, SIGINT);
  EXPECT_DOUBLE_EQ(s[0].stop_timeout_s, 5.0);
  EXPECT_TRUE(s[0].ends_run);
  EXPECT_TRUE(s[0].respawn);
  EXPECT_FALSE(s[1].respawn);
  EXPECT_EQ(s[1].stop_signal, SIGTERM);
  EXPECT_EQ(s[1].only_if, std::vector<std::string>{"log"});
  EXPECT_EQ(s[0].ready_file, "");
}

TEST(ServiceSet, ReadyFileIsSubstituted) {
  const std::string yaml = R"(
services:
  - name: logger
    command: [lcm-logger, "${log}"]
    ready_file: "${log}"
)";
  const auto s = parse_service_set(yaml, {{"log", "/tmp/run/log.lcmlog"}});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].ready_file, "/tmp/run/log.lcmlog");
}

TEST(ServiceSet, ErrorsNameTheProblem) {
  auto err = [](const std::string& yaml, std::map<std::string, std::string> vars = {}) {
    try {
      parse_service_set(yaml, vars);
    } catch (const ServiceSetError& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  };
  EXPECT_EQ(err("services:\n  - name: a\n    command: [x, \"${nope}\"]\n"), "unknown variable ${nope} in '${nope}'");
  EXPECT_EQ(err("services:\n  - name: a\n    command: [x]\n    stop_signal: KILL\n"),
            "a: stop_signal must be INT, TERM or HUP, got 'KILL'");
  EXPECT_EQ(err("services:\n  - name: a\n    command: [x]\n    respawns: true\n"), "a: unknown key 'respawns'");
  EXPECT_EQ(err("nothing: 1\n"), "services file: expected a 'services:' list");
}

TEST(ServiceSet, SystemdUnitFromSpec) {
  ServiceSpec s;
  s.name = "gpilot-hands";
  s.command = {"gpilot-hands", "--config", "/etc/gpilot.yaml"};
  s.stop_signal = SIGINT;
  s.stop_timeout_s = 4;
  const std::string unit = systemd_unit(s, "/opt/gpilot/bin", "gpilot-decide", "udpm://239.255.76.67:7667?ttl=1",
                                        "/etc/k", "gesture-pilot");
  EXPECT_NE(unit.find("ExecStart=/opt/gpilot/bin/gpilot-hands --config /etc/gpilot.yaml\n"), std::string::npos) << unit;
  EXPECT_NE(unit.find("After=network-online.target gpilot-decide.service\n"), std::string::npos);
  EXPECT_NE(unit.find("Wants=network-online.target gpilot-decide.service\n"), std::string::npos);
  EXPECT_NE(unit.find("\n[Service]\nUser=gesture-pilot\nGroup=gesture-pilot\n"), std::string::npos);
  for (const char* hardening : {"NoNewPrivileges=yes\n", "ProtectSystem=strict\n", "ProtectHome=yes\n",
                                "PrivateTmp=yes\n", "RestartPreventExitStatus=2\n"})
    EXPECT_NE(unit.find(hardening), std::string::npos) << hardening;
  EXPECT_NE(unit.find("Environment=GPILOT_BUS_KEY=/etc/k\n"), std::string::npos);
  EXPECT_EQ(systemd_unit(s, "/b", "", "u").find("User="), std::string::npos);  // no user: root
  EXPECT_NE(unit.find("Restart=always\n"), std::string::npos);
  EXPECT_NE(unit.find("KillSignal=SIGINT\n"), std::string::npos);
  EXPECT_NE(unit.find("TimeoutStopSec=4\n"), std::string::npos);
  EXPECT_NE(unit.find("Environment=GPILOT_LCM_URL=udpm://239.255.76.67:7667?ttl=1\n"), std::string::npos);
}

TEST(ServiceSet, ShippedFileParsesWithRunVariables) {
  std::ifstream in(std::string(GPILOT_SOURCE_DIR) + "/deploy/services.yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  const auto s = parse_service_set(ss.str(), {{"lcm_url", "u"}, {"config", "c"}, {"source_flag", "--synthetic"},
                                              {"source", "tour"}, {"capture_extra", ""}, {"backend", "sim"},
                                              {"mavlink", "udp:127.0.0.1:14580"}, {"log", "l"}, {"video_out", "v"}});
  ASSERT_GE(s.size(), 6u);
  EXPECT_EQ(s.front().name, "gpilot-record");  // records from the first message, frames too
  EXPECT_EQ(s.back().name, "gpilot-capture");  // frames flow only once every stage listens
  EXPECT_TRUE(s.back().ends_run);
}

TEST(ServiceSet, OnlyIfVariablesDecideWhatRuns) {
  ServiceSpec s;
  s.only_if = {"log"};
  EXPECT_TRUE(service_wanted(s, {{"log", "x.lcmlog"}}));
  EXPECT_FALSE(service_wanted(s, {{"log", ""}}));
  EXPECT_FALSE(service_wanted(s, {}));
  EXPECT_TRUE(service_wanted(ServiceSpec{}, {}));
}

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// deploy/systemd/*.service are what deploy/systemd/generate writes now (from deploy/services.yaml).
TEST(ServiceSet, CommittedSystemdUnitsAreTheGeneratedOnes) {
  namespace fs = std::filesystem;
  const fs::path shipped = fs::path(GPILOT_SOURCE_DIR) / "deploy/systemd";
  const fs::path fresh = fs::temp_directory_path() / ("gpilot-units-" + std::to_string(::getpid()));
  const std::string cmd = (shipped / "generate").string() + " " + fresh.string() + " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  int units = 0;
  for (const auto& f : fs::directory_iterator(fresh)) {
    ++units;
    const fs::path committed = shipped / f.path().filename();
    ASSERT_TRUE(fs::exists(committed)) << committed << " is missing: run deploy/systemd/generate";
    EXPECT_EQ(read_file(f.path()), read_file(committed)) << committed << " is stale: run deploy/systemd/generate";
  }
  for (const auto& f : fs::directory_iterator(shipped)) {
    if (f.path().extension() == ".service") {
      EXPECT_TRUE(fs::exists(fresh / f.path().filename())) << f.path() << " is no longer generated";
    }
  }
  EXPECT_EQ(units, 5);  // capture, tracker, hands, decide, flight: no logger and no video on the drone
  fs::remove_all(fresh);
}

}  // namespace
}  // namespace gpilot
