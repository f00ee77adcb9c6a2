// What gpilot-view's annotated MP4 costs a frame: H264Writer (libx264 at veryfast, one thread) against OpenCV's
// FFMPEG writer (avc1: libx264 at its medium default, on x264's threads), on 50 640x480 synthetic tour frames
// with a moving overlay. Both write to a temporary file; the frames are made before timing.
#include <benchmark/benchmark.h>

#include <filesystem>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "capture/synthetic_world.hpp"
#include "h264_writer.hpp"

using namespace gpilot;

namespace {

const std::vector<cv::Mat>& frames() {
  static const std::vector<cv::Mat> all = [] {
    const SyntheticWorld w(SyntheticParams{}, Scenario::load("tour"), 1);
    std::vector<cv::Mat> out;
    for (int i = 0; i < 50; ++i) {
      cv::Mat f = w.render(5.0 + i / 25.0, i, std::nullopt).bgr.clone();
      cv::rectangle(f, cv::Rect(250 + i, 120, 110, 280), cv::Scalar(0, 0, 255), 2);
      cv::putText(f, "seq " + std::to_string(i), cv::Point(10, 470), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255));
      out.push_back(f);
    }
    return out;
  }();
  return all;
}

std::string temp_mp4(const char* name) { return (std::filesystem::temp_directory_path() / name).string(); }

// One iteration writes the 50 frames to a file and closes it (the encoder's look-ahead is flushed there), and
// the CPU is the process's (OpenCV's writer encodes on x264's threads): ms per frame = CPU / 50.
// write_file(path, frames): "" or why it could not.
template <class WriteFile>
void bench_writer(benchmark::State& state, const char* name, WriteFile write_file) {
  const auto& f = frames();
  const std::string path = temp_mp4(name);
  for (auto _ : state)
    if (const std::string why = write_file(path, f); !why.empty()) return state.SkipWithError(why.c_str());
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(f.size()));
  state.counters["kB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e3;
  std::filesystem::remove(path);
}

void BM_VideoH264Writer(benchmark::State& state) {
  bench_writer(state, "gpilot_bench_h264.mp4", [](const std::string& path, const std::vector<cv::Mat>& f) {
    H264Writer w;
    if (std::string why = w.open(path, f[0].size(), 25.0); !why.empty()) return why;
    for (const cv::Mat& m : f) w.write(m);
    w.close();
    return std::string();
  });
}
BENCHMARK(BM_VideoH264Writer)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(5);

void BM_VideoOpenCvWriter(benchmark::State& state) {
  bench_writer(state, "gpilot_bench_opencv.mp4", [](const std::string& path, const std::vector<cv::Mat>& f) {
    cv::VideoWriter w(path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('a', 'v', 'c', '1'), 25.0, f[0].size());
    if (!w.isOpened()) return std::string("OpenCV's FFMPEG writer does not open avc1");
    for (const cv::Mat& m : f) w.write(m);
    w.release();
    return std::string();
  });
}
BENCHMARK(BM_VideoOpenCvWriter)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(5);

}  // namespace
