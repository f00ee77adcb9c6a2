// What a signed bus costs per message size: signing (the sender) and verifying (each receiver) with
// HMAC-SHA-256 (bus_signature.hpp), from a command (64 B) to a JPEG frame (50 kB) and raw 640x480 and
// 1280x720 BGR frames. The CAMERA decision in the README's security section is made on these figures.
#include <benchmark/benchmark.h>

#include <vector>

#include "bus_key.hpp"
#include "bus_signature.hpp"

namespace gpilot {
namespace {

BusKey bench_key() {
  BusKey k;
  for (size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = static_cast<uint8_t>(i * 13 + 1);
  k.id = bus_key_id(k.bytes);
  return k;
}

void BM_BusSign(benchmark::State& state) {
  const size_t n = static_cast<size_t>(state.range(0));
  std::vector<uint8_t> buf(n + kSignatureBytes, 0x5a);
  BusSigner signer(bench_key(), 1);
  int64_t t = 1'800'000'000'000'000;
  for (auto _ : state) benchmark::DoNotOptimize(signer.sign("CAMERA", buf.data(), n, ++t));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * n));
}
BENCHMARK(BM_BusSign)->Arg(64)->Arg(50'000)->Arg(640 * 480 * 3)->Arg(1280 * 720 * 3)->Unit(benchmark::kMicrosecond);

void BM_BusVerify(benchmark::State& state) {
  const size_t n = static_cast<size_t>(state.range(0));
  std::vector<uint8_t> buf(n + kSignatureBytes, 0x5a);
  BusSigner signer(bench_key(), 1);
  const int64_t t = 1'800'000'000'000'000;
  const size_t signed_size = signer.sign("CAMERA", buf.data(), n, t);
  for (auto _ : state) {
    BusVerifier verifier({bench_key()}, 1'000'000);  // fresh: the same message is not a replay
    benchmark::DoNotOptimize(verifier.verify("CAMERA", buf.data(), signed_size, t).why);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * n));
}
BENCHMARK(BM_BusVerify)->Arg(64)->Arg(50'000)->Arg(640 * 480 * 3)->Arg(1280 * 720 * 3)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gpilot
