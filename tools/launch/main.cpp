// gpilot-launch: starts the processes of deploy/services.yaml in order, restarts the ones that die,
// shows progress (time, frames, mode, each stage's rate) and stops them all cleanly, in reverse order, on
// Ctrl-C, at --duration, or when a service marked ends_run exits. Reads HEALTH, USER_TRACK and GESTURE_CMD; writes
// FLIGHT_CONTROL (with --engage) and its own HEALTH.
// A service with watchdog_s is watched as systemd would (sd_notify READY=1 / WATCHDOG=1 on a NOTIFY_SOCKET of
// ours): silent longer than that once ready, it is killed and restarted at once. Every child gets SIGTERM when
// the launcher dies, however it dies (PR_SET_PDEATHSIG): no stage flies on as an orphan.
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <memory>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clock.hpp"
#include "flight/flight_channels.hpp"
#include "log.hpp"
#include "notify_socket.hpp"
#include "paths.hpp"
#include "process_channels.hpp"
#include "service_cli.hpp"
#include "service_set.hpp"
#include "gpilot/user_track_t.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace gpilot {
namespace {

const char* kModeNames[] = {"HOVER", "FINE", "UP", "DOWN", "CLOSER", "FURTHER"};

struct Child {
  ServiceSpec spec;
  std::string path;
  pid_t pid = -1;
  int restarts = 0;
  int64_t restart_at = 0;  // monotonic us; 0 = none pending
  std::unique_ptr<NotifySocket> notify;  // watched services only
  bool ready = false;          // READY=1 from this instance: its watchdog runs
  int64_t last_ping = 0;       // monotonic us of its last READY/WATCHDOG
  int64_t frozen_since = 0;    // the last ping of an instance the watchdog killed; 0 = none (for the report)
};

std::string find_binary(const std::string& word, const std::string& bin_dir) {
  if (word.find('/') != std::string::npos) return word;
  const fs::path local = fs::path(bin_dir) / word;
  if (fs::exists(local)) return local.string();
  std::stringstream path(std::getenv("PATH") ? std::getenv("PATH") : "");
  for (std::string dir; std::getline(path, dir, ':');)
    if (!dir.empty() && fs::exists(fs::path(dir) / word)) return (fs::path(dir) / word).string();
  return "";
}

pid_t spawn(const Child& c) {
  // Everything the child needs is built before fork(): between fork and exec only async-signal-safe calls.
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(c.path.c_str()));
  for (size_t i = 1; i < c.spec.command.size(); ++i) argv.push_back(const_cast<char*>(c.spec.command[i].c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "NOTIFY_SOCKET=", 14) != 0 && std::strncmp(*e, "WATCHDOG_", 9) != 0) env_text.push_back(*e);
  if (c.notify) {
    // No WATCHDOG_PID: the child's pid is not known before fork, and sd_watchdog_enabled() accepts its absence.
    env_text.push_back("NOTIFY_SOCKET=" + c.notify->address());
    env_text.push_back("WATCHDOG_USEC=" + std::to_string(seconds_to_utime(c.spec.watchdog_s)));
  }
  std::vector<char*> envp;
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);  // own group: the terminal's Ctrl-C reaches the launcher, which stops children in order
    // The launcher gone (kill -9, a crash), the stage stops too; checked again after the call in case the
    // launcher died before it took effect.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(1);
    execve(c.path.c_str(), argv.data(), envp.data());
    const char* msg = "gpilot-launch: cannot exec a service\n";
    if (write(2, msg, std::strlen(msg)) < 0) _exit(127);
    _exit(127);
  }
  return pid;
}

// The watchdog of one watched child: reads its notify datagrams; once it has said READY=1, silence longer
// than watchdog_s is a frozen process: SIGKILL (a stopped process takes no other signal), and the restart
// follows from waitpid. Prints how long from its last ping to the restarted instance's READY=1.
void watch(Child& c, int64_t now, BusNode& node) {
  if (!c.notify || c.pid <= 0) return;
  const NotifyState s = c.notify->poll(c.pid);
  if (s.any()) c.last_ping = now;
  if (s.ready && !c.ready) {
    c.ready = true;
    if (c.frozen_since) {
      log_info("%s ready again %.2f s after its last watchdog ping", c.spec.name.c_str(), (now - c.frozen_since) * 1e-6);
      c.frozen_since = 0;
    }
  }
  if (s.stopping) c.ready = false;  // on its way out (STOPPING=1): silence is expected now
  if (!c.ready || now - c.last_ping <= seconds_to_utime(c.spec.watchdog_s)) return;
  log_warn("%s sent no watchdog ping for %.2f s (watchdog_s %.2f): frozen, SIGKILL", c.spec.name.c_str(),
           (now - c.last_ping) * 1e-6, c.spec.watchdog_s);
  node.set_state(health_t::STATE_DEGRADED, c.spec.name + " frozen: killed by the watchdog");
  kill(c.pid, SIGKILL);
  c.ready = false;
  c.frozen_since = c.last_ping;
}

// A recorder records once its file holds a message (lcm-logger flushes every 100 ms): the launcher's HEALTH
// gives it one. Until then a process started next could publish its CONFIG before the recorder listens.
void wait_for_recording(const std::string& name, const std::string& path, BusNode& node) {
  const int64_t end = monotonic_utime() + 5 * kMicrosPerSecond;
  for (;;) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (!ec && size > 0) return;
    if (monotonic_utime() >= end) break;
    node.publish_health();
    usleep(50000);
  }
  log_warn("%s: %s still empty after 5 s: starting the others anyway (their CONFIG may miss the log)", name.c_str(),
           path.c_str());
}

void stop_child(Child& c) {
  if (c.pid <= 0) return;
  kill(c.pid, c.spec.stop_signal);
  const int64_t deadline = monotonic_utime() + seconds_to_utime(c.spec.stop_timeout_s);
  int status = 0;
  while (monotonic_utime() < deadline) {
    if (waitpid(c.pid, &status, WNOHANG) == c.pid) {
      c.pid = -1;
      return;
    }
    usleep(20000);
  }
  log_warn("%s did not stop within %.1f s: SIGKILL", c.spec.name.c_str(), c.spec.stop_timeout_s);
  kill(c.pid, SIGKILL);
  waitpid(c.pid, &status, 0);
  c.pid = -1;
}

}  // namespace
}  // namespace gpilot

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-launch", "Start, watch, restart and stop the gesture-pilot processes of deploy/services.yaml.");
  std::string services_file = "deploy/services.yaml";
  std::vector<std::string> var_args;
  std::string systemd_dir, bus_key_file, systemd_user;
  double duration_s = 0;
  bool engage = false;
  std::string bin_dir = fs::canonical("/proc/self/exe").parent_path().string();
  cli.app().add_option("--services", services_file, "services file (relative paths: from the project root)");
  cli.app().add_option("--var", var_args, "name=value for ${name} in the services file (repeatable)");
  cli.app().add_option("--systemd", systemd_dir, "write one systemd unit per service into DIR and exit");
  cli.app().add_option("--systemd-bus-key", bus_key_file,
                       "with --systemd: the units' bus key file (Environment=GPILOT_BUS_KEY; needed at ttl > 0)");
  cli.app().add_option("--systemd-user", systemd_user, "with --systemd: the user the units run as (default: root)");
  cli.app().add_option("--duration", duration_s, "stop everything after this many seconds");
  cli.app().add_flag("--engage", engage, "send FLIGHT_CONTROL engage once gpilot-flight reports");
  cli.app().add_option("--bin-dir", bin_dir, "where the gpilot binaries are (default: beside this one)");

  return cli.run(argc, argv, [&](const Config& config) -> int {
    std::map<std::string, std::string> vars;
    for (const auto& a : var_args) {
      const auto eq = a.find('=');
      if (eq == std::string::npos) throw ServiceSetError("--var '" + a + "': expected name=value");
      vars[a.substr(0, eq)] = a.substr(eq + 1);
    }
    const std::string url = resolve_lcm_url(cli.lcm_url());
    vars.emplace("lcm_url", url);
    // the frames' URL (bus.frames_url, else derived from the bus URL): for a services file's own recorder
    vars.emplace("frames_url", frames_url_for(url, config.section<BusParams>("bus")));
    std::ifstream in(resolve_project_path(services_file));
    if (!in) throw ServiceSetError(services_file + ": cannot open");
    std::stringstream text;
    text << in.rdbuf();
    const auto specs = parse_service_set(text.str(), vars);

    if (!systemd_dir.empty()) {
      fs::create_directories(systemd_dir);
      std::string after;
      for (const auto& s : specs) {
        if (!service_wanted(s, vars)) continue;
        // A source that ends a run (a scenario, a file) is restarted by systemd like any other: on a companion
        // computer it is the camera, which does not end.
        std::ofstream(fs::path(systemd_dir) / (s.name + ".service")) << systemd_unit(s, fs::absolute(bin_dir).string(), after, url, bus_key_file, systemd_user);
        std::printf("wrote %s/%s.service\n", systemd_dir.c_str(), s.name.c_str());
        after = s.name;
      }
      return 0;
    }

    setenv("GPILOT_LCM_URL", url.c_str(), 1);
    BusNode node("gpilot-launch", url, config.section<BusParams>("bus"));
    std::map<std::string, health_t> health;
    int8_t mode = -1;
    subscribe(node, process_channels::kHealth, [&](const health_t& h, int64_t) { health[h.name] = h; });
    subscribe(node, flight_channels::kGestureCmd, [&](const gesture_cmd_t& g, int64_t) { mode = g.mode; });
    // Frames that made it through the tracker: one USER_TRACK each (listening to CAMERA would copy every image).
    long long frames = 0;
    subscribe(node, flight_channels::kUserTrack, [&](const user_track_t&, int64_t) { ++frames; });
    log_info("progress each second: frames tracked, decided mode, each stage's messages/s in>out");

    std::vector<Child> children;
    for (const auto& s : specs) {
      if (!service_wanted(s, vars)) continue;
      Child c;
      c.spec = s;
      c.path = find_binary(s.command[0], bin_dir);
      if (s.watchdog_s > 0) c.notify = std::make_unique<NotifySocket>(s.name);
      if (c.path.empty()) {
        if (s.optional) {
          log_warn("%s: not built, skipped", s.name.c_str());
          continue;
        }
        throw ServiceSetError(s.name + ": no executable '" + s.command[0] + "' in " + bin_dir + " or PATH");
      }
      c.pid = spawn(c);
      std::string command;
      for (const auto& w : s.command) command += " " + w;
      log_info("started %s (pid %d):%s", s.name.c_str(), c.pid, command.c_str());
      children.push_back(std::move(c));
      if (!s.ready_file.empty()) wait_for_recording(s.name, s.ready_file, node);
    }
    node.set_state(health_t::STATE_OK, "running " + std::to_string(children.size()) + " processes");

    const int64_t start = monotonic_utime();
    int exit_code = 0;
    int engage_sent = 0;
    node.every(0.05, [&] {
      const int64_t now = monotonic_utime();
      for (auto& c : children) {
        watch(c, now, node);
        int status = 0;
        if (c.pid > 0 && waitpid(c.pid, &status, WNOHANG) == c.pid) {
          c.pid = -1;
          const std::string how = WIFEXITED(status) ? "exited with status " + std::to_string(WEXITSTATUS(status))
                                                    : std::string("killed by signal ") + strsignal(WTERMSIG(status));
          // A source that reaches its end exits 0 and ends the run; one that crashes is restarted like any stage.
          if (c.spec.ends_run && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
            log_info("%s %s: run complete", c.spec.name.c_str(), how.c_str());
            exit_code = 0;
            node.stop();
            return;
          }
          if (c.spec.respawn) {
            // After a crash, half a second (no busy restart loop); a frozen stage is back at once.
            c.restart_at = c.frozen_since ? now : now + kMicrosPerSecond / 2;
            log_warn("%s %s: restarting", c.spec.name.c_str(), how.c_str());
          } else {
            log_warn("%s %s (not restarted)", c.spec.name.c_str(), how.c_str());
          }
          node.set_state(health_t::STATE_DEGRADED, c.spec.name + " " + how);
        }
        if (c.pid < 0 && c.restart_at > 0 && now >= c.restart_at) {
          c.restart_at = 0;
          c.ready = false;
          c.pid = spawn(c);
          ++c.restarts;
          node.set_state(health_t::STATE_OK, "restarted " + c.spec.name + " (" + std::to_string(c.restarts) + "x)");
        }
      }
      if (duration_s > 0 && now - start > seconds_to_utime(duration_s)) node.stop();
    });
    node.every(0.5, [&] {
      if (!engage || engage_sent >= 3 || !health.count("gpilot-flight")) return;
      flight_control_t fc{};
      fc.utime = wall_utime();
      fc.seq = engage_sent++;
      fc.command = flight_control_t::COMMAND_ENGAGE;
      fc.source = "gpilot-launch";
      publish(node, flight_channels::kFlightControl, fc);
      if (engage_sent == 1) log_info("engaged");
    });
    node.every(1.0, [&] {
      const double t = (monotonic_utime() - start) * 1e-6;
      std::string stages;
      for (const auto& c : children) {
        const auto it = health.find(c.spec.name);
        std::string shortname = c.spec.name.rfind("gpilot-", 0) == 0 ? c.spec.name.substr(7) : c.spec.name;
        char rates[64];
        if (c.pid < 0)
          stages += " " + shortname + " DOWN";
        else if (it != health.end() &&
                 std::snprintf(rates, sizeof rates, " %.0f>%.0f", it->second.rate_in_hz, it->second.rate_out_hz) > 0)
          stages += " " + shortname + rates;
      }
      log_info("[%6.1f s] frames %lld | mode %s |%s", t, frames, mode >= 0 && mode <= 5 ? kModeNames[mode] : "-",
               stages.c_str());
    });
    node.run();
    log_info("stopping %zu processes", children.size());
    for (auto it = children.rbegin(); it != children.rend(); ++it) stop_child(*it);
    return exit_code;
  });
}
