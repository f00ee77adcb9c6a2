// gpilot-keygen: makes a bus key file (32 random bytes as hex, mode 0600) for signed bus messages. Install
// the same file on the drone and the ground station and point bus.key_file (or GPILOT_BUS_KEY) at it.
#include <cstdio>
#include <string>

#include "bus_key.hpp"
#include "service_cli.hpp"

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-keygen",
                 "gpilot-keygen FILE: writes a new random bus key (mode 0600; never overwrites) and prints its id.\n"
                 "With --show-id, prints the id of an existing key instead (the id signatures name it by).");
  std::string path;
  bool show_id = false;
  cli.app().add_option("file", path, "the key file to write (or read, with --show-id)")->required();
  cli.app().add_flag("--show-id", show_id, "print the id of an existing key file");
  return cli.run(argc, argv, [&](const Config&) {
    const BusKey key = show_id ? load_bus_key(path) : make_bus_key_file(path);
    std::printf("%s: bus key id %08x\n", path.c_str(), key.id);
    return 0;
  });
}
