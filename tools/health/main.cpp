// gpilot-health: a terminal table of every gpilot process's HEALTH (state, rates, rejections, timing).
// Reads HEALTH; like every process it also publishes its own. --channels prints the table of every channel
// from the stages' declarations (DEVELOPERS.md holds it; a test compares).
#include <cstdio>
#include <map>
#include <string>

#include "service_cli.hpp"
#include "system/system_channels.hpp"

int main(int argc, char** argv) {
  gpilot::ServiceCli cli("gpilot-health", "Show the HEALTH of every gpilot process on the bus, once a second.");
  double duration_s = 0;
  cli.app().add_option("--duration", duration_s, "stop after this many seconds (default: until Ctrl-C)");
  bool channels = false;
  cli.app().add_flag("--channels", channels,
                     "print every channel (type, the processes that write and read it) as a Markdown table and exit");
  for (int i = 1; i < argc; ++i)  // no bus for the table: it is the declarations, not what is on the bus
    if (std::string(argv[i]) == "--channels")
      return cli.run(argc, argv, [](const gpilot::Config&) {
        std::fputs(gpilot::channel_table_markdown().c_str(), stdout);
        return 0;
      });
  return cli.run_node(argc, argv, [&](const gpilot::Config&, gpilot::BusNode& node) {
    std::map<std::string, gpilot::health_t> latest;
    std::map<std::string, double> cpu_percent;  // over the last report period, one core = 100
    subscribe(node, gpilot::process_channels::kHealth, [&](const gpilot::health_t& h, int64_t) {
      const auto before = latest.find(h.name);
      if (before != latest.end() && before->second.pid == h.pid && h.utime > before->second.utime)
        cpu_percent[h.name] = 100 * (h.cpu_s - before->second.cpu_s) / ((h.utime - before->second.utime) * 1e-6);
      latest[h.name] = h;
    });
    static const char* kStates[] = {"STARTING", "OK", "DEGRADED", "ERROR", "STOPPING"};
    node.every(1.0, [&] {
      std::printf("%-22s %-9s %8s %8s %8s %8s %7s %7s %6s  %s\n", "process", "state", "in/s", "out/s", "rejected",
                  "dropped", "p50 ms", "p99 ms", "CPU %", "detail / last rejection");
      for (const auto& [name, h] : latest)
        std::printf("%-22s %-9s %8.1f %8.1f %8lld %8lld %7.2f %7.2f %6.1f  %s%s%s\n", name.c_str(), kStates[h.state],
                    h.rate_in_hz, h.rate_out_hz, static_cast<long long>(h.rejected),
                    static_cast<long long>(h.dropped), h.processing_ms_p50, h.processing_ms_p99,
                    cpu_percent.count(name) ? cpu_percent[name] : 0.0,
                    h.state_detail.c_str(), h.last_reject_reason.empty() ? "" : " | ", h.last_reject_reason.c_str());
      std::printf("\n");
      std::fflush(stdout);
    });
    if (duration_s > 0) node.every(duration_s, [&] { node.stop(); });
    node.set_state(gpilot::health_t::STATE_OK, "monitoring");
    node.run();
    return 0;
  });
}
