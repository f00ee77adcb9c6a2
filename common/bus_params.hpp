// Parameters of the bus itself (section `bus`), read by every process: the signing keys and the per-stream
// rules BusNode applies before any handler.
#pragma once

#include <string>

namespace gpilot {

struct BusParams {
  std::string key_file;           //!< the deployment's bus key (gpilot-keygen); $GPILOT_BUS_KEY overrides
  std::string previous_key_file;  //!< also accepted (never used to sign) while a new key is rolled out
  double time_window_s = 2.0;     //!< a message's utime and signature time must be this close to its arrival

  template <class V>
  void visit(V& v) {
    v("key_file", key_file,
      "bus key file (32 random bytes, mode 0600; make one with gpilot-keygen). With a key every message is "
      "signed and only signed messages are accepted; a network bus (ttl > 0) needs one. $GPILOT_BUS_KEY overrides");
    v("previous_key_file", previous_key_file, "a second key that is accepted, not used to sign (key rotation)");
    v("time_window_s", time_window_s, 0.01, 3600.0,
      "a message whose utime or signature time is further than this from its arrival is rejected, s");
  }
};

}  // namespace gpilot
