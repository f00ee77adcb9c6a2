// Tracker costs on one core: FHOG of a DSST-sized window, one DSST frame (track + learn) on 640x480 for a
// near and a far person, the Haar face search on a 640x480 frame, the face re-check's, and a searching frame of
// the UserTracker (face scan step, and with tracker.person the person detector on one frame in every_frames).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "dsst.hpp"
#include "fhog.hpp"
#include "face_cascade.hpp"
#include "face_detector.hpp"
#include "user_tracker.hpp"
// The textured scene of the DSST known-answer tests.
#include "../../tests/unit/tracker/known_scene.hpp"

namespace {

void BM_FhogWindow(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat patch = gpilot::test::texture(cv::Size(100, 100), 11);
  gpilot::Fhog f;
  std::vector<cv::Mat> out;
  for (auto _ : state) {
    f.compute(patch, 4, out);
    benchmark::DoNotOptimize(out[0].data);
  }
}
BENCHMARK(BM_FhogWindow);

// One DSST frame at 640x480: the texture slides by a sub-pixel step each frame under a person-sized box.
void BM_DsstFrame640x480(benchmark::State& state) {
  cv::setNumThreads(1);
  const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  const cv::Mat tex = gpilot::test::texture(cv::Size(900, 700), 11);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 16; ++i)
    frames.push_back(gpilot::test::view(tex, cv::Point2d(450, 350), cv::Point2d(320 + 1.3 * std::sin(0.4 * i), 240 + 0.9 * std::cos(0.3 * i)),
                                1.0, cv::Size(640, 480)));
  gpilot::Dsst dsst{gpilot::DsstParams{}};
  dsst.init(frames[0], cv::Rect2d(320 - w / 2.0, 240 - h / 2.0, w, h));
  size_t i = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(dsst.update(frames[i]));
    i = (i + 1) % frames.size();
  }
}
BENCHMARK(BM_DsstFrame640x480)->Args({100, 260})->Args({40, 100})->Unit(benchmark::kMicrosecond);

void BM_FaceSearch640x480(benchmark::State& state) {
  cv::setNumThreads(1);
  gpilot::TrackerParams p;
  p.face.downscale = static_cast<double>(state.range(0));
  gpilot::FaceDetector faces(p, load_face_cascade(p));
  const cv::Mat frame = gpilot::test::texture(cv::Size(640, 480), 11);
  for (auto _ : state) benchmark::DoNotOptimize(faces.detect(frame));
}
BENCHMARK(BM_FaceSearch640x480)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The face re-check's search of its window (face_recheck_window of a body box around the expected face) on a
// textured 640x480 frame. Args: the expected face (px: 35 searched as shot, 12 enlarged), the pyramid step x 100
// (face.recheck_scale_factor).
void BM_FaceRecheck(benchmark::State& state) {
  cv::setNumThreads(1);
  gpilot::TrackerParams p;
  p.face.recheck_scale_factor = static_cast<double>(state.range(1)) / 100.0;
  gpilot::FaceDetector faces(p, load_face_cascade(p));
  const cv::Mat frame = gpilot::test::texture(cv::Size(640, 480), 11);
  const double face = static_cast<double>(state.range(0));
  const cv::Rect roi = gpilot::face_recheck_window(gpilot::body_from_face(cv::Rect2d(300, 100, face, face), p.body()), p);
  for (auto _ : state) benchmark::DoNotOptimize(faces.recheck(frame, roi, face, p.face_recheck_min_share));
}
BENCHMARK(BM_FaceRecheck)->Args({35, 110})->Args({35, 103})->Args({12, 110})->Args({12, 103})->Unit(benchmark::kMillisecond);

// A UserTracker SEARCHING a frame with nobody in it (the search's whole budget every frame): the mean over
// frames is the cost of a searching frame. Args: width, height, tracker.person.enabled.
void BM_UserTrackerSearching(benchmark::State& state) {
  cv::setNumThreads(1);
  gpilot::TrackerParams p;
  p.person.enabled = state.range(2) != 0;
  gpilot::UserTracker tracker(p, gpilot::load_tracker_models(p));
  const cv::Mat frame = gpilot::test::texture(cv::Size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))), 11);
  for (auto _ : state) benchmark::DoNotOptimize(tracker.process(frame));
}
BENCHMARK(BM_UserTrackerSearching)->Args({640, 480, 0})->Args({640, 480, 1})->Args({1280, 720, 0})->Args({1280, 720, 1})
    ->Iterations(100)->Unit(benchmark::kMillisecond);

}  // namespace
