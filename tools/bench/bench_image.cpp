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

#include <turbojpeg.h>

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

// libjpeg-turbo's DCT-scaled decode of the same frame at 1/denominator of each side (8x8 blocks inverse-
// transformed to 4x4, 2x2, 1x1: the entropy decoding stays whole): what a stage that needs fewer pixels would
// pay (issue 14: "where a stage needs fewer pixels, decode scaled"). Denominator 1 is image_to_mat's decode.
void BM_TurboJpegScaledDecode(benchmark::State& state) {
  const image_t msg = tour_frame(static_cast<int>(state.range(0)), image_t::PIXEL_FORMAT_JPEG);
  const int denom = static_cast<int>(state.range(1));
  const int w = (msg.width + denom - 1) / denom, h = (msg.height + denom - 1) / denom;  // TJSCALED
  cv::Mat out(h, w, CV_8UC3);
  tjhandle tj = tjInitDecompress();
  for (auto _ : state)
    if (tjDecompress2(tj, msg.data.data(), static_cast<unsigned long>(msg.size), out.data, w, static_cast<int>(out.step), h,
                      TJPF_BGR, 0) != 0) {
      state.SkipWithError(tjGetErrorStr2(tj));
      break;
    }
  tjDestroy(tj);
  state.counters["pixels"] = static_cast<double>(w) * h;
}
BENCHMARK(BM_TurboJpegScaledDecode)->ArgsProduct({{640, 1280}, {1, 2, 4, 8}})->Unit(benchmark::kMillisecond);

}  // namespace
