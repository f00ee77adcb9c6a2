// The set of gpilot processes, declared once in deploy/services.yaml (in the manner of procman): command,
// respawn, stop signal, stop time, start order. The same list drives ./deploy/run (gpilot-launch), the
// end-to-end tests and the systemd units for a companion computer.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace gpilot {

struct ServiceSpec {
  std::string name;                  //!< process name, also the HEALTH name it publishes
  std::vector<std::string> command;  //!< argv; a bare argv[0] is looked up in the build's bin/ first
  bool respawn = true;               //!< restart when it dies
  int stop_signal = 15;              //!< SIGTERM unless the file says INT
  double stop_timeout_s = 3.0;       //!< then SIGKILL
  bool ends_run = false;             //!< its exit (status 0) ends the whole run
  bool optional = false;             //!< skip with a message when its binary is missing
  std::vector<std::string> only_if;  //!< started only when each named variable is non-empty
  // > 0: the process must tell it is alive (sd_notify WATCHDOG=1) at least this often once it said READY=1;
  // a process silent for longer is killed and restarted. systemd: Type=notify + WatchdogSec; gpilot-launch:
  // the same protocol on a NOTIFY_SOCKET of its own (notify_socket.hpp).
  double watchdog_s = 0;
  // Not empty: the next service starts once this file is non-empty (lcm-logger: it records), at most 5 s later,
  // so the others' first messages (each process's CONFIG, which a replay reads) are in the log.
  std::string ready_file;
};

class ServiceSetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses services.yaml text; ${var} in commands is replaced from vars (an unknown var is an error).
// A command word that becomes empty after substitution is dropped (optional flags).
std::vector<ServiceSpec> parse_service_set(const std::string& yaml_text, const std::map<std::string, std::string>& vars);

// "${a} x ${b}" with vars; throws ServiceSetError naming an unknown variable.
std::string substitute(const std::string& text, const std::map<std::string, std::string>& vars);

// Whether the service runs with these variables (every only_if variable non-empty).
bool service_wanted(const ServiceSpec& spec, const std::map<std::string, std::string>& vars);

// A systemd unit for one service: ExecStart from bin_dir, Restart from respawn, KillSignal, TimeoutStopSec,
// ordered After= the service before it; with watchdog_s, Type=notify and WatchdogSec (systemd then kills a
// process that stops pinging, WatchdogSignal=SIGKILL, and Restart= brings it back). bus_key: the bus key
// file the units use (Environment=GPILOT_BUS_KEY), "" for none. user: User=/Group= the stage runs as, "" for
// root. Every unit is hardened (NoNewPrivileges, ProtectSystem=strict, ProtectHome, PrivateTmp), waits for
// network-online.target, and is not restarted after exit status 2 (a refused config).
std::string systemd_unit(const ServiceSpec& spec, const std::string& bin_dir, const std::string& after,
                         const std::string& lcm_url, const std::string& bus_key = "", const std::string& user = "");

}  // namespace gpilot
