// Benchmarks of the hands stage on one core: the whole stage per 640x480 frame (skin lookup in the search
// rectangle, opening, removals, integral image, Alg. 1 and Alg. 2), and its skin lookup alone over a full frame.
// Frames are made before timing: the key poses of the synthetic `tour` (with their true user boxes), a drawn
// person pointing out, and a worst case of random colours (a tenth of the rectangle skin, in specks).
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>

#include "capture/synthetic_world.hpp"
#include "hands/hand_detector.hpp"
#include "paths.hpp"

using namespace gpilot;

namespace {

const cv::Rect2f kBox(260, 120, 120, 300);  // a user about 3 m away in a 640x480 frame

HandDetector make_detector() {
  const HandsParams p;
  return HandDetector(p, SkinClassifier(SkinModel::load(resolve_project_path(p.skin.model)), p.skin.threshold));
}

cv::Mat drawn_person() {
  const cv::Scalar skin(90, 120, 170);
  cv::Mat frame(480, 640, CV_8UC3);
  cv::RNG rng(3);
  rng.fill(frame, cv::RNG::UNIFORM, cv::Scalar(120, 40, 0), cv::Scalar(255, 120, 80));  // bluish, not skin
  cv::rectangle(frame, cv::Rect(295, 125, 50, 60), skin, cv::FILLED);   // face
  cv::rectangle(frame, cv::Rect(265, 250, 18, 24), skin, cv::FILLED);   // resting left hand
  cv::rectangle(frame, cv::Rect(150, 190, 110, 16), skin, cv::FILLED);  // stretched right forearm
  cv::rectangle(frame, cv::Rect(130, 185, 24, 26), skin, cv::FILLED);   // its hand
  return frame;
}

cv::Mat random_colours() {
  cv::Mat frame(480, 640, CV_8UC3);
  cv::RNG rng(5);
  rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
  return frame;
}

void run_stage(benchmark::State& state, const cv::Mat& frame) {
  HandDetector d = make_detector();
  int kind = 0;
  for (auto _ : state) {
    const HandResult r = d.detect(frame, kBox);
    kind = static_cast<int>(r.kind);
    benchmark::DoNotOptimize(r.vector);
  }
  state.counters["kind"] = kind;
  state.counters["roi_px"] = d.last_roi().area();
  state.counters["skin_px"] = cv::countNonZero(d.last_mask());
}

// Every key pose of the tour, one per iteration in turn.
void BM_HandsStage_TourKeyPoses(benchmark::State& state) {
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("tour"), 1);
  std::vector<SyntheticFrame> frames;
  for (const double t : world.scenario().key_times())
    frames.push_back(world.render(t, static_cast<int64_t>(t * world.params().fps), std::nullopt));
  HandDetector d = make_detector();
  size_t i = 0;
  for (auto _ : state) {
    const SyntheticFrame& f = frames[i++ % frames.size()];
    benchmark::DoNotOptimize(d.detect(f.bgr, f.truth.user_box).vector);
  }
  state.counters["poses"] = static_cast<double>(frames.size());
}

void BM_HandsStage_PersonPointing(benchmark::State& state) { run_stage(state, drawn_person()); }
void BM_HandsStage_RandomColours(benchmark::State& state) { run_stage(state, random_colours()); }

void BM_SkinLookup_FullFrame(benchmark::State& state) {
  const HandsParams p;
  const SkinClassifier skin(SkinModel::load(resolve_project_path(p.skin.model)), p.skin.threshold);
  const cv::Mat frame = random_colours();
  cv::Mat mask;
  for (auto _ : state) {
    skin.classify(frame, mask);
    benchmark::DoNotOptimize(mask.data);
  }
  state.SetItemsProcessed(state.iterations() * frame.total());
}

}  // namespace

BENCHMARK(BM_HandsStage_TourKeyPoses)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HandsStage_PersonPointing)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HandsStage_RandomColours)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SkinLookup_FullFrame)->Unit(benchmark::kMillisecond);
