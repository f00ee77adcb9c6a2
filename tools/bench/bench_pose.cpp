// Benchmarks of the pose core on one thread: the person detector over a 640x480 frame, each landmark model on
// one ROI, and the estimator's tracked frame (crop, lite, decoding, smoothing, next ROI). The frame is the
// synthetic tour's OUT pose, rendered before timing; models from models/pose (deploy/setup). The argument is
// PoseParams::fast_depthwise: 1, the depthwise convolutions on ours; 0, on OpenCV's own.
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>

#include "capture/synthetic_world.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "pose/pose_estimator.hpp"

using namespace gpilot;

namespace {

SyntheticFrame out_pose_frame() {
  const SyntheticWorld world(SyntheticParams{}, Scenario::load("tour"), 1);
  return world.render(world.scenario().key_time_of(ground_truth_t::GESTURE_OUT).value_or(0.0), 0, std::nullopt);
}

void BM_PoseDetector(benchmark::State& state) {
  const SyntheticFrame f = out_pose_frame();
  PoseParams p;
  p.fast_depthwise = state.range(0) != 0;
  cv::setNumThreads(p.threads);  // as gpilot-hands sets it (opencv_threads_of)
  PersonDetector detector(p, PoseModels::load(p).detector);
  size_t found = 0;
  for (auto _ : state) found = detector.detect(f.bgr).size();
  state.counters["detections"] = static_cast<double>(found);
}

void run_landmarks(benchmark::State& state, const char* model) {
  const SyntheticFrame f = out_pose_frame();
  PoseParams p;
  p.model = model;
  p.fast_depthwise = state.range(0) != 0;
  cv::setNumThreads(p.threads);  // as gpilot-hands sets it (opencv_threads_of)
  PoseModels models = PoseModels::load(p);
  PersonDetector detector(p, models.detector);
  const auto d = choose_user_detection(detector.detect(f.bgr), f.truth.user_box);
  if (!d) {
    state.SkipWithError("no person detected");
    return;
  }
  const PoseRoi roi = roi_from_alignment(d->keypoints[0], d->keypoints[1], static_cast<float>(p.roi_scale));
  LandmarkModel landmark(models.landmark);
  float flag = 0;
  for (auto _ : state) flag = landmark.run(f.bgr, roi).pose_flag;
  state.counters["pose_flag"] = flag;
}

void BM_PoseLandmarkLite(benchmark::State& state) { run_landmarks(state, "lite"); }
void BM_PoseLandmarkFull(benchmark::State& state) { run_landmarks(state, "full"); }

// One tracked frame: the estimator seeded once (detector) before timing, then the same frame again and again at
// advancing times (the ROI from the previous frame's auxiliary points; no detector).
void BM_PoseEstimatorTracking(benchmark::State& state) {
  const SyntheticFrame f = out_pose_frame();
  PoseParams p;
  p.fast_depthwise = state.range(0) != 0;
  PoseEstimator pose(p, PoseModels::load(p));
  int64_t utime = 0;
  pose.estimate(f.bgr, f.truth.user_box, utime);
  bool found = false;
  for (auto _ : state) {
    utime += 40000;
    found = pose.estimate(f.bgr, f.truth.user_box, utime).found;
  }
  state.counters["found"] = found;
  state.counters["detector_runs"] = static_cast<double>(pose.counters().detector_runs);
}

}  // namespace

BENCHMARK(BM_PoseDetector)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PoseLandmarkLite)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PoseLandmarkFull)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PoseEstimatorTracking)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
