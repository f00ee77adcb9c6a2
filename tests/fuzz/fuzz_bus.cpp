// Fuzz target: what BusNode does to a datagram before it decodes it, on a signed bus: the signature check
// (BusVerifier: trailer, key id, HMAC, time window, per-sender order) and the per-stream rules (StreamGuard),
// over a sequence of datagrams and arrival times. Any input gives a verdict, never a crash; a datagram is
// accepted only when it carries a valid signature, and then never twice.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "bus_signature.hpp"
#include "fuzz_input.hpp"
#include "stream_guard.hpp"

namespace {

gpilot::BusKey key_of(uint8_t fill) {
  gpilot::BusKey k;
  k.bytes.fill(fill);
  k.id = gpilot::bus_key_id(k.bytes);
  return k;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  gpilot::fuzz::Input in(data, size);
  const int64_t t0 = 1'800'000'000'000'000;
  gpilot::BusVerifier verifier({key_of(1), key_of(2)}, 2'000'000);
  gpilot::BusSigner signer(key_of(1), 77);
  gpilot::StreamGuard guard(2'000'000);
  std::set<std::vector<uint8_t>> accepted;
  for (int step = 0; step < 16 && !in.empty(); ++step) {
    const int64_t arrival = t0 + in.in(-5'000'000, 5'000'000);
    const std::string channel = in.flag() ? "CAMERA" : "FLIGHT_CONTROL";
    std::vector<uint8_t> datagram;
    if (in.flag()) {  // a genuinely signed message, maybe altered afterwards
      datagram = in.bytes(in.in(0, 64));
      const size_t n = datagram.size();
      datagram.resize(n + gpilot::kSignatureBytes);
      datagram.resize(signer.sign(channel, datagram.data(), n, t0 + in.in(-5'000'000, 5'000'000)));
      if (in.flag() && !datagram.empty()) datagram[in.in(0, static_cast<int64_t>(datagram.size()) - 1)] ^= in.byte() | 1;
    } else {
      datagram = in.bytes(in.in(0, 200));
    }
    const auto r = verifier.verify(channel, datagram.data(), datagram.size(), arrival);
    if (r.why.empty()) {
      if (r.message_size + gpilot::kSignatureBytes != datagram.size()) gpilot::fuzz::fail("accepted with a wrong size");
      if (!accepted.insert(datagram).second) gpilot::fuzz::fail("the same signed datagram accepted twice");
    }
    (void)gpilot::message_size_of(datagram.data(), datagram.size());
    (void)guard.admit(channel + std::to_string(in.byte() % 4), t0 + in.in(-5'000'000, 5'000'000),
                      in.raw<int64_t>(), arrival);
  }
  return 0;
}
