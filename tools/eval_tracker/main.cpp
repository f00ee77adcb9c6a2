// gpilot-eval-tracker: runs our tracker (and with --compare OpenCV's CSRT, KCF, legacy MOSSE and dlib's
// correlation_tracker) over one sequence, lock-step on the same frames, and reports OTB's success AUC,
// precision at 20 px, mean IoU, frames lost and the trackers' own frames per second. Frames whose truth is
// UAV123's NaN line (target not visible) are not scored; each tracker's behaviour there is reported instead.
// Input: an OTB folder (img/ + groundtruth_rect.txt or init_rect.txt) or --log with CAMERA + GROUND_TRUTH.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/tracking/tracking_legacy.hpp>

#ifdef GPILOT_HAVE_DLIB
#include <dlib/image_transforms/fhog.h>  // correlation_tracker.h uses it without including it
#include <dlib/image_processing/correlation_tracker.h>
#include <dlib/opencv/cv_image.h>
#endif

#include "dsst.hpp"
#include "face_cascade.hpp"
#include "json_out.hpp"
#include "log.hpp"
#include "metrics.hpp"
#include "occluder.hpp"
#include "sequence.hpp"
#include "service_cli.hpp"
#include "user_tracker.hpp"

namespace gpilot {
namespace {

// CPU time of this thread, microseconds. The machine is shared: wall time would count other processes'
// time slices; with --threads 1 every tracker (OpenCV's included) runs on this thread.
int64_t thread_cpu_utime() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

// One tracker under test. update() gives the box of the frame, or none when the tracker says it lost it.
class Runner {
 public:
  explicit Runner(std::string name) : name_(std::move(name)) {}
  virtual ~Runner() = default;
  virtual void init(const cv::Mat& frame, const cv::Rect2d& box) = 0;
  virtual std::optional<cv::Rect2d> update(const cv::Mat& frame) = 0;
  const std::string& name() const { return name_; }
  //! True while the tracker is looking for its target rather than following it (the next update searches).
  virtual bool searching() const { return false; }
  //! --auto-init: one frame of the tracker's own search for its target; the box once it has started a track.
  virtual std::optional<cv::Rect2d> start_itself(const cv::Mat&) { return std::nullopt; }

  // Book-keeping of the evaluation.
  cv::Rect2d last;
  bool started = false;
  int lost = 0;
  int64_t update_us = 0, search_us = 0;
  int updates = 0, search_updates = 0;
  std::vector<double> ious, errors, psr;
  std::vector<FrameVerdict> verdicts;  //!< every frame after the start, for the absent-target report
  std::string state;                   //!< this frame's state as the tracker names it (for --trace)

 private:
  std::string name_;
};

// init: a manual box. start_itself (--auto-init): the tracker's own face search starts the track, as in the
// service, and the track then knows the user's clothes (a manual box's does not: its re-checks are not gated
// by them, and a look-alike's face re-anchored it).
class UserTrackerRunner : public Runner {
 public:
  explicit UserTrackerRunner(const TrackerParams& p) : Runner("gpilot UserTracker"), t_(p, load_tracker_models(p)) {}
  void init(const cv::Mat& frame, const cv::Rect2d& box) override {
    t_.set_box(box);
    t_.process(frame);
  }
  bool searching() const override { return t_.last().status != TrackStatus::kTracking; }
  std::optional<cv::Rect2d> start_itself(const cv::Mat& frame) override {
    const TrackOutput o = t_.process(frame);
    if (o.status != TrackStatus::kTracking) return std::nullopt;
    return o.box;
  }
  std::optional<cv::Rect2d> update(const cv::Mat& frame) override {
    const TrackOutput o = t_.process(frame);
    psr.push_back(o.confidence);
    state = o.status == TrackStatus::kTracking ? "tracking" : o.status == TrackStatus::kLost ? "lost" : "searching";
    if (o.facing != Facing::kUnknown) state += o.facing == Facing::kAway ? " away" : " toward";
    if (o.status != TrackStatus::kTracking) return std::nullopt;
    return o.box;
  }

 private:
  UserTracker t_;
};

class DsstRunner : public Runner {
 public:
  explicit DsstRunner(const DsstParams& p) : Runner("gpilot DSST alone"), d_(p) {}
  void init(const cv::Mat& frame, const cv::Rect2d& box) override { d_.init(frame, box); }
  std::optional<cv::Rect2d> update(const cv::Mat& frame) override {
    const DsstEstimate e = d_.update(frame);
    psr.push_back(e.psr);
    return e.box;
  }

 private:
  Dsst d_;
};

class OpenCvRunner : public Runner {
 public:
  OpenCvRunner(std::string name, cv::Ptr<cv::Tracker> t) : Runner(std::move(name)), t_(std::move(t)) {}
  void init(const cv::Mat& frame, const cv::Rect2d& box) override { t_->init(frame, box); }
  std::optional<cv::Rect2d> update(const cv::Mat& frame) override {
    cv::Rect r;
    if (!t_->update(frame, r)) return std::nullopt;
    return cv::Rect2d(r);
  }

 private:
  cv::Ptr<cv::Tracker> t_;
};

class MosseRunner : public Runner {
 public:
  MosseRunner() : Runner("OpenCV MOSSE (legacy)"), t_(cv::legacy::TrackerMOSSE::create()) {}
  void init(const cv::Mat& frame, const cv::Rect2d& box) override { t_->init(frame, box); }
  std::optional<cv::Rect2d> update(const cv::Mat& frame) override {
    cv::Rect2d r;
    if (!t_->update(frame, r)) return std::nullopt;
    return r;
  }

 private:
  cv::Ptr<cv::legacy::TrackerMOSSE> t_;
};

#ifdef GPILOT_HAVE_DLIB
class DlibRunner : public Runner {
 public:
  DlibRunner() : Runner("dlib correlation_tracker") {}
  void init(const cv::Mat& frame, const cv::Rect2d& b) override {
    t_.start_track(dlib::cv_image<dlib::bgr_pixel>(frame), dlib::drectangle(b.x, b.y, b.x + b.width - 1, b.y + b.height - 1));
  }
  std::optional<cv::Rect2d> update(const cv::Mat& frame) override {
    psr.push_back(t_.update(dlib::cv_image<dlib::bgr_pixel>(frame)));
    const dlib::drectangle r = t_.get_position();
    return cv::Rect2d(r.left(), r.top(), r.width(), r.height());
  }

 private:
  dlib::correlation_tracker t_;
};
#endif

std::string num(double v, int prec = 4) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s.precision(prec);
  s << std::fixed << v;
  return s.str();
}

struct Result {
  std::string name;
  TrackScores scores;
  bool has_truth = false;
  int lost = 0;
  double fps = 0, ms = 0, psr_min = 0, psr_mean = 0;
  int search_frames = 0;
  double search_ms = 0;  //!< mean cost of a frame processed while not tracking
  cv::Rect2d final_box;
  AbsenceBehaviour absence;
};

std::string int_list(const std::vector<int>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
  return s;
}

// One tracker's scores into a --json object (the table's digits; NaN: no truth -> null).
void add_result_fields(gpilot::json& j, const Result& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  j["success_auc"] = gpilot::rounded(r.has_truth ? r.scores.success_auc : nan, 4);
  j["precision_20px"] = gpilot::rounded(r.has_truth ? r.scores.precision_20px : nan, 4);
  j["mean_iou"] = gpilot::rounded(r.has_truth ? r.scores.mean_iou : nan, 4);
  j["frames_lost"] = r.lost;
  j["fps"] = gpilot::rounded(r.fps, 1);
  j["ms_per_frame"] = gpilot::rounded(r.ms, 3);
  j["final_box"] = {gpilot::rounded(r.final_box.x, 1), gpilot::rounded(r.final_box.y, 1),
                    gpilot::rounded(r.final_box.width, 1), gpilot::rounded(r.final_box.height, 1)};
  j["absent_frames"] = r.absence.absent_frames;
  j["absent_reported_lost"] = r.absence.reported_lost;
  j["refound_after"] = r.absence.refound_after;
  j["frames_searching"] = r.search_frames;
  j["ms_per_frame_searching"] = gpilot::rounded(r.search_ms, 3);
}

int run_eval(const Config& config, const std::string& seq_dir, const std::string& log_path,
             const std::string& synthetic, bool auto_init,
             bool compare, bool json, const std::string& plot, const std::string& trace_path, int threads, int repeat,
             const std::vector<Occluder>& occluders, const cv::Mat& occluder_texture, bool reanchor_manual,
             const std::string& synthetic_truth) {
  cv::setNumThreads(threads);
  TrackerParams params = config.section<TrackerParams>("tracker");
  // Started on the annotation (not --auto-init), our tracker keeps that box's shape, as every other tracker here
  // does and as the boxes are scored; --reanchor-manual: as the service takes a TRACKER_INIT box.
  params.manual_box_keeps_shape = !reanchor_manual;
  // Each tracker runs over the sequence in a pass of its own, the frames read again for each (reading is not
  // timed). Run frame by frame in turn, each started its frame from caches the others had just filled (CSRT's
  // 25 ms a frame), and the first to run paid every first use of a frame size: ours, first, ran
  // uav123_person12_1 at 1.91 ms a frame with --compare and at 1.59 without.
  const auto open_plain_source = [&]() -> std::unique_ptr<FrameSource> {
    if (!log_path.empty()) return open_lcm_log(log_path);
    if (!synthetic.empty()) {
#ifdef GPILOT_HAVE_SYNTHETIC
      return open_synthetic(synthetic, synthetic_truth == "face" ? SyntheticTruthBox::kFace : SyntheticTruthBox::kUserBox);
#else
      throw std::runtime_error("--synthetic: built without the capture stage's synthetic world");
#endif
    }
    return open_otb(seq_dir);
  };
  const auto open_source = [&]() -> std::unique_ptr<FrameSource> {
    if (occluders.empty()) return open_plain_source();
    return occluded(open_plain_source(), occluders, occluder_texture);
  };
  std::string seq_name = open_source()->name();  // opened once first: a bad sequence fails before any pass

  // The trackers by index, made afresh for each pass (--repeat).
  std::vector<std::function<std::unique_ptr<Runner>()>> makers;
  makers.emplace_back([&] { return std::make_unique<UserTrackerRunner>(params); });
  makers.emplace_back([&] { return std::make_unique<DsstRunner>(params.dsst); });
  if (compare) {
    makers.emplace_back([] { return std::make_unique<OpenCvRunner>("OpenCV CSRT", cv::TrackerCSRT::create()); });
    makers.emplace_back([] { return std::make_unique<OpenCvRunner>("OpenCV KCF", cv::TrackerKCF::create()); });
    makers.emplace_back([] { return std::make_unique<MosseRunner>(); });
#ifdef GPILOT_HAVE_DLIB
    makers.emplace_back([] { return std::make_unique<DlibRunner>(); });
#else
    log_warn("dlib not found at build time (libdlib-dev): its correlation_tracker is left out");
#endif
  }
  std::vector<std::unique_ptr<Runner>> runners;

  std::string init_how = auto_init ? "face" : reanchor_manual ? "ground_truth, re-anchored on the face" : "ground_truth";
  int frames = 0, truth_frames = 0, init_frame = -1;
  cv::Rect2d init_box;
  // --trace: a row a frame from the start, written once every pass is done.
  std::vector<std::string> trace_truth, trace_ours;
  std::vector<std::vector<std::string>> trace_cells(makers.size());
  // The frames per second of each tracker: the median of its passes' (the boxes are the first pass's; a pass
  // gives the same boxes every time, the trackers being deterministic).
  std::vector<std::vector<double>> pass_ms(makers.size()), pass_search_ms(makers.size());
  // One pass of tracker ri (r, made afresh) over the sequence; record: the pass whose boxes are scored and traced.
  const auto run_pass = [&](Runner& r, size_t ri, bool record) {
    const bool first = ri == 0 && record;  // ours: decides the start (its own face search with --auto-init) for all
    const std::unique_ptr<FrameSource> src = open_source();
    int frame = 0;
    EvalFrame f;
    while (src->next(f)) {
      ++frame;
      if (frame % 50 == 0) std::fprintf(stderr, "%s: frame %d\n", r.name().c_str(), frame);
      if (first) ++frames;
      if (!r.started) {
        std::optional<cv::Rect2d> box;
        if (ri == 0) {
          box = f.truth;
          if (auto_init) {
            // Our tracker searches as the service does (its face search within the per-frame budget, each face's
            // body checked and fitted against the image); the others start on the box it starts its track with,
            // that frame. (The tool's own full-frame search each frame took 0.3 s a frame where the user is 5 m away.)
            const int64_t t0 = thread_cpu_utime();
            box = r.start_itself(f.image);
            r.search_us += thread_cpu_utime() - t0;
            ++r.search_updates;
          }
          if (!box && !auto_init && frame == 1) throw std::runtime_error("the first frame has no ground-truth box to start from");
          if (box && first) {
            init_frame = frame;
            init_box = *box;
          }
        } else if (frame == init_frame) {
          box = init_box;
        }
        if (box) {
          if (!(ri == 0 && auto_init)) {  // else started itself on this frame
            const int64_t t0 = thread_cpu_utime();
            r.init(f.image, *box);
            r.update_us += thread_cpu_utime() - t0;
          }
          r.last = *box;
          r.started = true;
        }
        if (f.truth && !f.absent) {
          if (first) ++truth_frames;
          r.ious.push_back(box ? iou(*box, *f.truth) : 0.0);
          r.errors.push_back(box ? centre_error(*box, *f.truth) : std::numeric_limits<double>::infinity());
        }
        continue;
      }
      // A frame whose truth says the target is not visible is not scored (UAV123's toolkit does the same);
      // how each tracker behaves there is reported apart (AbsenceBehaviour).
      if (first && f.truth) ++truth_frames;
      const bool searching = r.searching();
      const int64_t t0 = thread_cpu_utime();
      const auto box = r.update(f.image);
      const int64_t dt = thread_cpu_utime() - t0;
      r.update_us += dt;
      ++r.updates;
      if (searching) {
        r.search_us += dt;
        ++r.search_updates;
      }
      if (box)
        r.last = *box;
      else
        ++r.lost;
      FrameVerdict v;
      v.absent = f.absent;
      v.reported = box.has_value();
      if (f.truth) {
        v.iou = box ? iou(*box, *f.truth) : (r.last.area() > 0 ? iou(r.last, *f.truth) : 0.0);
        r.ious.push_back(v.iou);
        r.errors.push_back(centre_error(r.last, *f.truth));
      }
      r.verdicts.push_back(v);
      if (record && !trace_path.empty()) {
        char cell[160];
        if (first) {
          const cv::Rect2d t = f.truth.value_or(cv::Rect2d());
          std::snprintf(cell, sizeof cell, "%d,%.1f,%.1f,%.1f,%.1f,%d", frame, t.x, t.y, t.width, t.height, f.absent ? 1 : 0);
          trace_truth.emplace_back(cell);
          std::snprintf(cell, sizeof cell, ",%s,%.2f", r.state.c_str(), r.psr.empty() ? 0.0 : r.psr.back());
          trace_ours.emplace_back(cell);
        }
        std::snprintf(cell, sizeof cell, ",%.1f,%.1f,%.1f,%.1f,%d,%.3f", r.last.x, r.last.y, r.last.width, r.last.height, box ? 1 : 0, v.iou);
        trace_cells[ri].emplace_back(cell);
      }
    }
    if (first && frames == 0) throw std::runtime_error("the sequence has no frames");
    if (first && init_frame < 0) throw std::runtime_error("our tracker started no track in any frame (--auto-init: no face found)");
  };
  for (size_t ri = 0; ri < makers.size(); ++ri)
    for (int pass = 0; pass < repeat; ++pass) {
      std::unique_ptr<Runner> r = makers[ri]();
      std::fprintf(stderr, "%s: pass %d of %d\n", r->name().c_str(), pass + 1, repeat);
      run_pass(*r, ri, pass == 0);
      pass_ms[ri].push_back(r->updates ? r->update_us / 1000.0 / (r->updates + 1) : 0.0);  // + the init frame
      pass_search_ms[ri].push_back(r->search_updates ? r->search_us / 1000.0 / r->search_updates : 0.0);
      if (pass == 0) runners.push_back(std::move(r));
    }
  if (!trace_path.empty()) {
    FILE* trace = std::fopen(trace_path.c_str(), "w");
    if (!trace) throw std::runtime_error(trace_path + ": cannot write the trace");
    std::fprintf(trace, "frame,truth_x,truth_y,truth_w,truth_h,absent");
    for (size_t i = 0; i < runners.size(); ++i) std::fprintf(trace, ",t%zu_x,t%zu_y,t%zu_w,t%zu_h,t%zu_box,t%zu_iou", i, i, i, i, i, i);
    std::fprintf(trace, ",ours_state,ours_psr\n");
    for (size_t row = 0; row < trace_truth.size(); ++row) {
      std::fputs(trace_truth[row].c_str(), trace);
      for (const auto& cells : trace_cells) std::fputs(row < cells.size() ? cells[row].c_str() : ",,,,,,", trace);
      std::fprintf(trace, "%s\n", trace_ours[row].c_str());
    }
    std::fclose(trace);
  }

  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  std::vector<Result> results;
  for (size_t ri = 0; ri < runners.size(); ++ri) {
    const auto& r = runners[ri];
    Result res;
    res.name = r->name();
    res.has_truth = truth_frames > 1;
    res.scores = score(r->ious, r->errors);
    res.lost = r->lost;
    res.ms = median(pass_ms[ri]);
    res.fps = res.ms > 0 ? 1000.0 / res.ms : 0.0;
    res.final_box = r->last;
    res.absence = absence_behaviour(r->verdicts);
    res.search_frames = r->search_updates;
    res.search_ms = median(pass_search_ms[ri]);
    if (!r->psr.empty()) {
      res.psr_min = *std::min_element(r->psr.begin(), r->psr.end());
      for (double v : r->psr) res.psr_mean += v / static_cast<double>(r->psr.size());
    }
    results.push_back(res);
  }

  if (!plot.empty() && truth_frames > 1) {
    std::vector<PlotCurve> curves;
    for (const auto& r : results) curves.push_back({r.name + " " + num(r.scores.success_auc, 3), r.scores.success});
    write_success_plot(plot, "Success plot: " + seq_name, curves);
  }

  const Result& ours = results[0];
  if (json) {
    gpilot::json out = {{"sequence", seq_name}, {"frames", frames},   {"frames_with_truth", truth_frames},
                        {"init", init_how},        {"init_frame", init_frame}, {"threads", threads},
                        {"repeat", repeat},
                        {"tracker", ours.name}};
    add_result_fields(out, ours);
    out["psr_min"] = gpilot::rounded(ours.psr_min, 2);
    out["psr_mean"] = gpilot::rounded(ours.psr_mean, 2);
    out["trackers"] = gpilot::json::array();
    for (const auto& r : results) {
      gpilot::json t = {{"name", r.name}};
      add_result_fields(t, r);
      out["trackers"].push_back(t);
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
  }
  std::printf("%s: %d frames (%d with ground truth), initialised from %s at frame %d, %d OpenCV thread(s)\n",
              seq_name.c_str(), frames, truth_frames, init_how.c_str(), init_frame, threads);
  if (ours.absence.absent_frames > 0)
    std::printf("%d frames where the truth says the target is not visible (NaN): not scored\n", ours.absence.absent_frames);
  std::printf("\n");
  std::printf("%-26s %8s %9s %9s %6s %9s %9s\n", "tracker", "AUC", "prec@20", "mean IoU", "lost", "fps", "ms/frame");
  for (const auto& r : results)
    std::printf("%-26s %8s %9s %9s %6d %9.1f %9.3f   final box %.0f,%.0f %.0fx%.0f\n", r.name.c_str(), num(r.has_truth ? r.scores.success_auc : NAN, 3).c_str(),
                num(r.has_truth ? r.scores.precision_20px : NAN, 3).c_str(), num(r.has_truth ? r.scores.mean_iou : NAN, 3).c_str(),
                r.lost, r.fps, r.ms, r.final_box.x, r.final_box.y, r.final_box.width, r.final_box.height);
  std::printf("\nours: PSR min %.2f, mean %.2f; final box %.1f %.1f %.1f %.1f; %d frames searching (LOST or SEARCHING) at"
              " %.2f ms/frame\n", ours.psr_min, ours.psr_mean, ours.final_box.x, ours.final_box.y, ours.final_box.width,
              ours.final_box.height, ours.search_frames, ours.search_ms);
  if (ours.absence.absent_frames > 0) {
    std::printf("\nwhile the target was not visible (%d frames), and after it came back (visible frames until IoU >= 0.5;"
                " -1: never):\n", ours.absence.absent_frames);
    for (const auto& r : results)
      std::printf("  %-26s reported lost on %3d of %d; re-found after [%s]\n", r.name.c_str(), r.absence.reported_lost,
                  r.absence.absent_frames, int_list(r.absence.refound_after).c_str());
  }
  if (results.size() > 2 && ours.has_truth) {
    std::printf("\n%s against the anchors:\n", ours.name.c_str());
    for (size_t i = 2; i < results.size(); ++i) {
      const Result& a = results[i];
      std::printf("  %-26s AUC %s (%+.3f), %.2fx its speed\n", a.name.c_str(),
                  ours.scores.success_auc >= a.scores.success_auc ? "better" : "WORSE",
                  ours.scores.success_auc - a.scores.success_auc, a.ms > 0 ? a.ms / ours.ms : 0.0);
    }
  }
  return 0;
}

}  // namespace
}  // namespace gpilot

int main(int argc, char** argv) {
  gpilot::ServiceCli cli("gpilot-eval-tracker",
                         "Tracker evaluation on an OTB sequence folder or an LCM log (CAMERA + GROUND_TRUTH):\n"
                         "success AUC, precision at 20 px, mean IoU, frames lost, frames per second.");
  std::string seq, log, plot, synthetic, trace, occluder_image, synthetic_truth = "user";
  std::vector<std::string> occlude;
  bool auto_init = false, compare = false, json = false, reanchor_manual = false;
  int threads = 1, repeat = 1;
  auto& app = cli.app();
  app.add_option("sequence", seq, "OTB-layout folder: img/*.jpg and groundtruth_rect.txt (1-based) or init_rect.txt (0-based)");
  app.add_option("--log", log, "LCM log with CAMERA and GROUND_TRUTH instead of a folder");
  app.add_option("--synthetic", synthetic, "a synthetic-world scenario (e.g. tour) instead of a folder; truth = its user box");
  app.add_option("--synthetic-truth", synthetic_truth, "--synthetic: the truth is the user box (user) or the face box (face: a head "
                 "annotated as OTB's face clips are; frames without a face are not scored)")->check(CLI::IsMember({"user", "face"}));
  app.add_flag("--auto-init", auto_init, "start from the face detector's body box instead of the first ground truth (our UserTracker from its "
                 "own face search, as in the service)");
  app.add_flag("--reanchor-manual", reanchor_manual, "started on the ground truth, re-anchor our box on the preset body box of the face "
               "its re-check finds, as the service does a TRACKER_INIT box (default: the box keeps its shape, as the truth is drawn)");
  app.add_flag("--compare", compare, "also run OpenCV CSRT, KCF, MOSSE and dlib correlation_tracker on the same frames");
  app.add_flag("--json", json, "print one JSON object on stdout");
  app.add_option("--plot", plot, "write the success plot to this PNG");
  app.add_option("--trace", trace, "write every frame's truth, each tracker's box and IoU, and our state (and whether the user faces the drone) and PSR to this CSV");
  app.add_option("--repeat", repeat, "run each tracker over the sequence this many times: its speed is the median pass's "
                 "(a short clip's time is noisy)")->check(CLI::Range(1, 100));
  app.add_option("--occlude", occlude, "paint an occluder over the frames: x,y,w,h (frame pixels) or x,y,w,h@first-last (frames "
                 "1-based, 'first-' to the end); repeatable. A target partly hidden, the same pixels for every tracker");
  app.add_option("--occluder-image", occluder_image, "the occluders' texture, resized to each (default: mid grey), e.g. "
                 "data/backgrounds/building.jpg");
  app.add_option("--threads", threads, "OpenCV threads (default 1: the cost on one core; times are thread CPU time)");
  return cli.run(argc, argv, [&](const gpilot::Config& config) {
    if (!seq.empty() + !log.empty() + !synthetic.empty() != 1) {
      gpilot::log_error("give one of: a sequence folder, --log, --synthetic");
      return 2;
    }
    std::vector<gpilot::Occluder> occluders;
    for (const std::string& spec : occlude) {
      const auto o = gpilot::parse_occluder(spec);
      if (!o) {
        gpilot::log_error("--occlude %s: not x,y,w,h or x,y,w,h@first-last (w, h > 0; 1 <= first <= last)", spec.c_str());
        return 2;
      }
      occluders.push_back(*o);
    }
    cv::Mat texture;
    if (!occluder_image.empty()) {
      texture = cv::imread(occluder_image, cv::IMREAD_COLOR);
      if (texture.empty()) {
        gpilot::log_error("--occluder-image %s: not an image that loads", occluder_image.c_str());
        return 2;
      }
    }
    return gpilot::run_eval(config, seq, log, synthetic, auto_init, compare, json, plot, trace, threads, repeat, occluders, texture, reanchor_manual, synthetic_truth);
  });
}
