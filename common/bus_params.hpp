// Parameters of the bus itself (section `bus`), read by every process: the signing keys, the per-stream
// rules BusNode applies before any handler, and where the frames travel.
#pragma once

#include <string>

namespace gpilot {

struct BusParams {
  std::string key_file;           //!< the deployment's bus key (gpilot-keygen); $GPILOT_BUS_KEY overrides
  std::string previous_key_file;  //!< also accepted (never used to sign) while a new key is rolled out
  double time_window_s = 2.0;     //!< a message's utime and signature time must be this close to its arrival
  // Frames on a multicast port of their own: a process that never subscribes to CAMERA (decide, flight,
  // launch, health) then has no socket that the kernel copies 25 frames a second into (issue 14).
  std::string frames_url;                 //!< "" = derived from the bus URL (frames_url_for)
  // The camera's per-frame outputs: its frames, and the synthetic world's truth about each (read from logs).
  std::string frames_channels = "CAMERA|GROUND_TRUTH";  //!< the channels carried on frames_url (an LCM regex)

  template <class V>
  void visit(V& v) {
    v("key_file", key_file,
      "bus key file (32 random bytes, mode 0600; make one with gpilot-keygen). With a key every message is "
      "signed and only signed messages are accepted; a network bus (ttl > 0) needs one. $GPILOT_BUS_KEY overrides");
    v("previous_key_file", previous_key_file, "a second key that is accepted, not used to sign (key rotation)");
    v("time_window_s", time_window_s, 0.01, 3600.0,
      "a message whose utime or signature time is further than this from its arrival is rejected, s");
    v("frames_url", frames_url,
      "LCM URL of the frames (frames_channels): empty = the bus URL's group with port + 1 (same options); the bus "
      "URL itself = one bus for everything; memq:// and other non-udpm buses carry the frames themselves");
    v("frames_channels", frames_channels,
      "channels sent on frames_url instead of the bus URL (an LCM regex): the camera's per-frame outputs; a process "
      "that subscribes to none of them receives nothing per frame from the camera");
  }
};

}  // namespace gpilot
