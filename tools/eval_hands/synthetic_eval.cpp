#include "synthetic_eval.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture/synthetic_world.hpp"
#include "clock.hpp"
#include "hands/hands_core_factory.hpp"
#include "hands/hand_overlay.hpp"
#include "hands/hands_params.hpp"
#include "hands_score.hpp"
#include "tracker/tracker_params.hpp"

namespace gpilot {

namespace {

const char* kKinds[3] = {"NONE", "OUT", "FRONT"};

}  // namespace

int run_synthetic_eval(const SyntheticEvalOptions& o, const Config& config) {
  const auto hands = config.section<HandsParams>("hands");
  const auto tracker = config.section<TrackerParams>("tracker");
  const SyntheticWorld world(config.section<SyntheticParams>("synthetic"), Scenario::load(o.scenario), o.seed);
  const auto method = make_hand_method(hands);

  const double fps = world.params().fps;
  const int64_t frames = static_cast<int64_t>(std::floor(world.scenario().duration_s() * fps));
  int64_t confusion[3][3] = {};
  std::vector<double> angle_err, length_err_rel, length_err_px, ms;
  int64_t front_total = 0, front_right = 0, front_detected = 0, front_detected_right = 0, scored = 0;
  int written = 0, steady = 0, last_truth = -1;
  bool png_for_kind[3] = {false, false, false};
  int error_pngs = 0;
  int64_t last_error_png = -1000000;
  if (!o.png_dir.empty()) std::filesystem::create_directories(o.png_dir);
  std::FILE* csv = o.csv_path.empty() ? nullptr : std::fopen(o.csv_path.c_str(), "w");
  if (!o.csv_path.empty() && !csv) throw std::runtime_error("cannot write " + o.csv_path);
  if (csv) std::fprintf(csv, "frame,t_s,truth_kind,kind,truth_x,truth_y,x,y,hand_skin,skin_outside,skin_inside,pose_reading\n");

  for (int64_t i = 0; i < frames; i += o.stride) {
    const SyntheticFrame f = world.render(static_cast<double>(i) / fps, i, std::nullopt);
    const int64_t t0 = monotonic_utime();
    // The face as the tracker hands it over: on the first frame and at each re-check (tracker.face_recheck_frames).
    const int recheck = std::max(1, tracker.face_recheck_frames);
    const bool face_frame = i == 0 || (tracker.face_recheck_frames > 0 && i % recheck < o.stride);
    const HandsOutput r =
        method->observe(f.bgr, UserView{f.truth.user_box, face_frame ? std::optional<cv::Rect2f>(f.truth.face_box) : std::nullopt, 1},
                        std::llround(1e6 * static_cast<double>(i) / fps));
    ms.push_back(static_cast<double>(monotonic_utime() - t0) / 1000.0);
    const int truth = std::clamp(f.truth.expected_kind, 0, 2), got = static_cast<int>(r.kind);
    ++confusion[truth][got];
    ++scored;
    steady = truth == last_truth ? steady + 1 : 0;
    last_truth = truth;
    const cv::Point2f tv = f.truth.expected_vector;
    if (csv) {
      const HandResult none;
      const HandResult& d = r.skin ? r.skin->detection : none;
      std::fprintf(csv, "%lld,%.3f,%s,%s,%.1f,%.1f,%.1f,%.1f,%d,%d,%d,\"%s\"\n", static_cast<long long>(i), static_cast<double>(i) / fps,
                   kKinds[truth], kKinds[got], tv.x, tv.y, r.vector.x, r.vector.y, d.hand_skin, d.skin_outside, d.skin_inside,
                   r.pose ? r.pose->reading.c_str() : "");
    }
    if (truth == 1 && got == 1) {
      angle_err.push_back(angle_between_deg(r.vector, tv));
      const double lt = std::hypot(tv.x, tv.y), lg = std::hypot(r.vector.x, r.vector.y);
      length_err_px.push_back(std::abs(lg - lt));
      if (lt > 0) length_err_rel.push_back(std::abs(lg - lt) / lt);
    }
    if (truth == 2) {
      ++front_total;
      const bool right_side = (r.vector.y < 0) == (tv.y < 0);
      if (got == 2) {
        ++front_detected;
        front_detected_right += right_side;
        front_right += right_side;
      }
    }
    // PNGs: the first steady frame of each kind (held 10 frames), then wrong kinds at least 2 s apart.
    const bool steady_pick = steady >= 10 / o.stride && !png_for_kind[truth];
    const bool error_pick = truth != got && error_pngs < o.pngs / 2 && i - last_error_png >= static_cast<int64_t>(2 * fps);
    if (!o.png_dir.empty() && written < o.pngs && (steady_pick || error_pick)) {
      png_for_kind[truth] = png_for_kind[truth] || steady_pick;
      if (!steady_pick) {
        ++error_pngs;
        last_error_png = i;
      }
      cv::Mat img = f.bgr.clone();
      draw_hand_overlay(img, r);
      const cv::Point2f from = truth == 1 ? f.truth.shoulder_centre : f.truth.body_centre;
      if (truth != 0) cv::arrowedLine(img, from, from + tv, cv::Scalar(255, 0, 255), 1, cv::LINE_AA, 0, 0.08);
      char text[160];
      std::snprintf(text, sizeof text, "frame %lld t %.2f s  truth %s  got %s", static_cast<long long>(i),
                    static_cast<double>(i) / fps, kKinds[truth], kKinds[got]);
      cv::putText(img, text, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
      cv::putText(img, text, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
      char name[64];
      std::snprintf(name, sizeof name, "/frame_%05lld_%s_%s.png", static_cast<long long>(i), kKinds[truth], kKinds[got]);
      cv::imwrite(o.png_dir + name, img);
      ++written;
    }
    if ((i / o.stride) % 50 == 0) std::fprintf(stderr, "\r%lld/%lld frames", static_cast<long long>(i), static_cast<long long>(frames));
  }
  std::fprintf(stderr, "\n");
  if (csv) std::fclose(csv);
  int64_t correct = 0;
  for (int k = 0; k < 3; ++k) correct += confusion[k][k];
  const double accuracy = scored ? static_cast<double>(correct) / static_cast<double>(scored) : 0;
  const double front_rate = front_total ? static_cast<double>(front_right) / static_cast<double>(front_total) : 0;
  const double front_rate_detected =
      front_detected ? static_cast<double>(front_detected_right) / static_cast<double>(front_detected) : 0;
  auto count_truth = [&](int k) { return confusion[k][0] + confusion[k][1] + confusion[k][2]; };
  if (o.json) {
    std::printf("{\"scenario\":\"%s\",\"seed\":%llu,\"user_box\":\"truth\",\"frames\":%lld,\"kind_accuracy\":%.4f,",
                o.scenario.c_str(), static_cast<unsigned long long>(o.seed), static_cast<long long>(scored), accuracy);
    std::printf("\"confusion\":{\"rows\":\"truth\",\"cols\":\"detected\",\"order\":[\"NONE\",\"OUT\",\"FRONT\"],\"counts\":[");
    for (int k = 0; k < 3; ++k)
      std::printf("%s[%lld,%lld,%lld]", k ? "," : "", static_cast<long long>(confusion[k][0]),
                  static_cast<long long>(confusion[k][1]), static_cast<long long>(confusion[k][2]));
    std::printf("]},\"out_frames\":%lld,\"out_scored\":%zu,\"angle_error_median_deg\":%.3f,\"angle_error_p90_deg\":%.3f,"
                "\"angle_error_max_deg\":%.3f,\"length_error_median_rel\":%.4f,\"length_error_median_px\":%.2f,",
                static_cast<long long>(count_truth(1)), angle_err.size(), median(angle_err), percentile(angle_err, 0.9),
                percentile(angle_err, 1.0), median(length_err_rel), median(length_err_px));
    std::printf("\"front_frames\":%lld,\"front_higher_lower_success\":%.4f,\"front_higher_lower_given_detected\":%.4f,"
                "\"ms_per_frame_median\":%.4f,\"ms_per_frame_p99\":%.4f,\"pngs\":%d}\n",
                static_cast<long long>(front_total), front_rate, front_rate_detected, median(ms), percentile(ms, 0.99), written);
  } else {
    std::printf("scenario %s (seed %llu), %lld frames scored, TRUE user box (tracker not involved)\n\n", o.scenario.c_str(),
                static_cast<unsigned long long>(o.seed), static_cast<long long>(scored));
    std::printf("confusion (rows truth, columns detected)\n%8s %8s %8s %8s\n", "", "NONE", "OUT", "FRONT");
    for (int k = 0; k < 3; ++k)
      std::printf("%8s %8lld %8lld %8lld\n", kKinds[k], static_cast<long long>(confusion[k][0]),
                  static_cast<long long>(confusion[k][1]), static_cast<long long>(confusion[k][2]));
    std::printf("\nkind accuracy               %.2f %%\n", 100 * accuracy);
    std::printf("OUT angle error             median %.2f deg, p90 %.2f, max %.2f (%zu frames)\n", median(angle_err),
                percentile(angle_err, 0.9), percentile(angle_err, 1.0), angle_err.size());
    std::printf("OUT length error            median %.1f %% (%.1f px)\n", 100 * median(length_err_rel), median(length_err_px));
    std::printf("FRONT higher/lower right    %.2f %% of %lld FRONT frames (%.2f %% of those detected FRONT; paper 85.45 %%)\n",
                100 * front_rate, static_cast<long long>(front_total), 100 * front_rate_detected);
    std::printf("time                        median %.3f ms, p99 %.3f ms per frame\n", median(ms), percentile(ms, 0.99));
    if (written) std::printf("annotated PNGs              %d in %s\n", written, o.png_dir.c_str());
  }
  return 0;
}

}  // namespace gpilot
