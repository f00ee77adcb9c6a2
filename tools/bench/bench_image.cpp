// What a JPEG CAMERA frame costs each stage that reads it: image_to_mat (libjpeg-turbo's TurboJPEG API
// straight into BGR) against cv::imdecode of the same bytes (the path before), and a raw BGR8 frame's
// image_to_mat (a wrap, no copy), at 640x480 and 1280x720, on a synthetic tour frame encoded at capture's
// default quality and chroma subsampling. The figures behind the JPEG default (issue: perceive in 1.5 ms, log a minute in 60 MB).
#include <benchmark/benchmark.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture/capture_params.hpp"
#include "capture/synthetic_world.hpp"
#include "image_codec.hpp"

using namespace gpilot;

namespace {

image_t tour_frame(int width, int8_t format) {
  static const SyntheticWorld w(SyntheticParams{}, Scenario::load("tour"), 1);
  cv::Mat bgr = w.render(6.5, 0, std::nullopt).bgr;
  const cv::Size size(width, width == 1280 ? 720 : width * 3 / 4);  // 640x480 or 1280x720
  if (bgr.size() != size) cv::resize(bgr, bgr, size, 0, 0, cv::INTER_LINEAR);
  const CaptureParams capture;
  JpegChroma chroma = JpegChroma::k444;
  jpeg_chroma_from_name(capture.jpeg_chroma, chroma);
  return mat_to_image(bgr, 0, 0, format, capture.jpeg_quality, chroma);
}

void BM_ImageToMatJpeg(benchmark::State& state) {
  const image_t msg = tour_frame(static_cast<int>(state.range(0)), image_t::PIXEL_FORMAT_JPEG);
  cv::Mat out;
  for (auto _ : state) benchmark::DoNotOptimize(image_to_mat(msg, out));
  state.counters["bytes"] = static_cast<double>(msg.size);
}
BENCHMARK(BM_ImageToMatJpeg)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);

void BM_ImdecodeJpeg(benchmark::State& state) {
  const image_t msg = tour_frame(static_cast<int>(state.range(0)), image_t::PIXEL_FORMAT_JPEG);
  for (auto _ : state)
    benchmark::DoNotOptimize(cv::imdecode(cv::Mat(1, msg.size, CV_8UC1, const_cast<uint8_t*>(msg.data.data())), cv::IMREAD_UNCHANGED));
}
BENCHMARK(BM_ImdecodeJpeg)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);

void BM_ImageToMatRaw(benchmark::State& state) {
  const image_t msg = tour_frame(static_cast<int>(state.range(0)), image_t::PIXEL_FORMAT_BGR8);
  cv::Mat out;
  for (auto _ : state) benchmark::DoNotOptimize(image_to_mat(msg, out));
  state.counters["bytes"] = static_cast<double>(msg.size);
}
BENCHMARK(BM_ImageToMatRaw)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);

}  // namespace
