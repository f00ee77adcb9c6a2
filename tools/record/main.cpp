// gpilot-record: records every channel of the bus AND of the frames URL (bus.frames_url: CAMERA and
// GROUND_TRUTH travel on a port of their own, issue 14) into one LCM log, the format lcm-logger writes, so that gpilot-report,
// gpilot-replay and lcm-logplayer read one file as before. lcm-logger listens to one URL: run one per URL
// for two files instead. Events are written in arrival order (EventOrder, held reorder_ms), each with its
// receive time; the file is flushed every 100 ms (gpilot-launch's ready_file waits for a non-empty file).
#include <cstdio>

#include <lcm/lcm-cpp.hpp>

#include "event_order.hpp"
#include "log.hpp"
#include "service_cli.hpp"

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-record",
                 "Record every channel of the bus and of the frames URL (bus.frames_url) into one LCM log, in arrival\n"
                 "order (lcm-logger's format). Stops on SIGINT/SIGTERM.");
  std::string path, channels = ".*";
  double reorder_ms = 100;
  int queue = 100;
  cli.app().add_option("log", path, "the LCM log to write (overwritten)")->required();
  cli.app().add_option("--channels", channels, "record only these channels (an LCM regex; default every one)");
  cli.app().add_option("--reorder-ms", reorder_ms, "hold events this long to write them in arrival order")
      ->check(CLI::Range(0.0, 5000.0));
  cli.app().add_option("--queue", queue,
                       "messages LCM holds per URL while the disk is slow (arrivals beyond are lost, as\n"
                       "gpilot-report's log_gaps then say)")
      ->check(CLI::Range(1, 100000));
  return cli.run_node(argc, argv, [&](const Config&, BusNode& node) -> int {
    lcm::LogFile out(path, "w");
    if (!out.good()) throw std::runtime_error(path + ": cannot write log");
    EventOrder order;
    int64_t eventnum = 0, bytes = 0;
    const auto write = [&](const EventOrder::Event& e) {
      lcm::LogEvent ev{};
      ev.eventnum = eventnum++;
      ev.timestamp = e.utime;
      ev.channel = e.channel;
      ev.datalen = static_cast<int32_t>(e.data.size());
      ev.data = const_cast<uint8_t*>(e.data.data());
      out.writeEvent(&ev);
      node.stats().published();  // HEALTH's messages out: events written
      bytes += ev.datalen;
    };
    node.subscribe_raw(channels, [&](const std::string& ch, const void* data, size_t size, int64_t recv_utime) {
      order.add(recv_utime, ch, data, size);
      node.stats().accepted();  // HEALTH's messages in (gpilot-launch's progress line, gpilot-health)
    }, queue);
    const int64_t hold = static_cast<int64_t>(reorder_ms * 1000);
    node.every(0.1, [&] {
      order.release_before(wall_utime() - hold, write);
      std::fflush(out.getFilePtr());
      node.set_state(health_t::STATE_OK, std::to_string(eventnum) + " events, " + std::to_string(bytes >> 20) +
                                             " MB in " + path);
    });
    log_info("recording %s and %s into %s", node.url().c_str(), node.frames_url().c_str(), path.c_str());
    node.run();
    node.drain();
    order.release_before(INT64_MAX, write);
    std::fflush(out.getFilePtr());
    log_info("%lld events, %lld bytes in %s", static_cast<long long>(eventnum), static_cast<long long>(bytes),
             path.c_str());
    return 0;
  });
}
