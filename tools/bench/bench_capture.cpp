// Benchmarks of the synthetic world on one core, 640x480: rendering a frame (background, person, ground
// truth) in a held pose of the tour, the same with every nuisance on (shake, noise, blur, JPEG round trip,
// distractor), and rendering plus publishing it as a BGR8 CAMERA image on memq:// (the capture loop's work
// per frame, without pacing). The worlds are built before timing.
#include <benchmark/benchmark.h>

#include "bus_node.hpp"
#include "capture/capture_channels.hpp"
#include "capture/synthetic_world.hpp"
#include "image_codec.hpp"

using namespace gpilot;

namespace {

const SyntheticWorld& tour() {
  static const SyntheticWorld w(SyntheticParams{}, Scenario::load("tour"), 1);
  return w;
}

const SyntheticWorld& nuisances() {
  static const SyntheticWorld w(
      SyntheticParams{},
      Scenario::parse("background: data/backgrounds/home.jpg\n"
                      "keyframes: [{t: 0, right_arm: out, noise_sigma: 6, shake_deg: 0.8, blur_px: 5, jpeg_quality: 40,"
                      " distractor: true}]\n",
                      "bench"),
      1);
  return w;
}

void BM_SyntheticRender(benchmark::State& state) {
  const SyntheticWorld& w = tour();
  int64_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(w.render(6.5, i++, std::nullopt));
}
BENCHMARK(BM_SyntheticRender)->Unit(benchmark::kMillisecond);

void BM_SyntheticRenderAllNuisances(benchmark::State& state) {
  const SyntheticWorld& w = nuisances();
  int64_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(w.render(1.0, i++, std::nullopt));
}
BENCHMARK(BM_SyntheticRenderAllNuisances)->Unit(benchmark::kMillisecond);

void BM_SyntheticRenderAndPublish(benchmark::State& state) {
  const SyntheticWorld& w = tour();
  BusNode node("bench", "memq://");
  int64_t i = 0;
  for (auto _ : state) {
    const SyntheticFrame f = w.render(6.5, i, CameraPose{0.2, 0.1, -1.5, 0.02});
    publish(node, capture_channels::kCamera, mat_to_image(f.bgr, i, i));
    node.drain();
    ++i;
  }
}
BENCHMARK(BM_SyntheticRenderAndPublish)->Unit(benchmark::kMillisecond);

}  // namespace
