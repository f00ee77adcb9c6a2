// OTB folders and LCM logs as frame sources (see sequence.hpp).
#include "sequence.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "image_codec.hpp"
#ifdef GPILOT_HAVE_SYNTHETIC
#include "capture/synthetic_params.hpp"
#include "capture/synthetic_world.hpp"
#endif
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/image_t.hpp"

namespace gpilot {
namespace fs = std::filesystem;

namespace {
std::istringstream fields(const std::string& line) {
  std::string s = line;
  std::replace_if(s.begin(), s.end(), [](char c) { return c == ',' || c == '\t'; }, ' ');
  return std::istringstream(s);
}
}  // namespace

bool is_absent_line(const std::string& line) {
  std::istringstream in = fields(line);
  std::string w;
  int n = 0;
  while (in >> w) {
    std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (w != "nan") return false;
    ++n;
  }
  return n == 4;
}

std::optional<cv::Rect2d> parse_box(const std::string& line) {
  std::istringstream in = fields(line);
  double v[4];
  for (double& x : v)
    if (!(in >> x) || !std::isfinite(x)) return std::nullopt;
  if (v[2] <= 0 || v[3] <= 0) return std::nullopt;
  return cv::Rect2d(v[0], v[1], v[2], v[3]);
}

namespace {

class OtbSource : public FrameSource {
 public:
  explicit OtbSource(const std::string& dir) : dir_(dir) {
    const fs::path img = fs::path(dir) / "img";
    if (!fs::is_directory(img)) throw std::runtime_error(dir + ": no img/ folder (OTB layout expected)");
    for (const auto& e : fs::directory_iterator(img))
      if (e.path().extension() == ".jpg" || e.path().extension() == ".png") files_.push_back(e.path().string());
    std::sort(files_.begin(), files_.end());
    if (files_.empty()) throw std::runtime_error(dir + "/img: no .jpg or .png frames");
    const fs::path gt = fs::path(dir) / "groundtruth_rect.txt";
    const fs::path init = fs::path(dir) / "init_rect.txt";
    // OTB boxes are 1-based (MATLAB); init_rect.txt of cf_tracking is 0-based.
    const bool otb = fs::exists(gt);
    if (!otb && !fs::exists(init)) throw std::runtime_error(dir + ": neither groundtruth_rect.txt nor init_rect.txt");
    std::ifstream in(otb ? gt : init);
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      if (is_absent_line(line)) {
        boxes_.push_back(std::nullopt);
        continue;
      }
      auto b = parse_box(line);
      if (!b) throw std::runtime_error((otb ? gt : init).string() + ":" + std::to_string(n) + ": not a box: " + line);
      if (otb) {
        b->x -= 1;
        b->y -= 1;
      }
      boxes_.push_back(*b);
    }
    if (boxes_.empty()) throw std::runtime_error(dir + ": the box file is empty");
  }
  bool next(EvalFrame& out) override {
    if (i_ >= files_.size()) return false;
    out.image = cv::imread(files_[i_], cv::IMREAD_COLOR);
    if (out.image.empty()) throw std::runtime_error(files_[i_] + ": does not decode");
    out.truth = i_ < boxes_.size() ? boxes_[i_] : std::nullopt;
    out.absent = i_ < boxes_.size() && !boxes_[i_];
    ++i_;
    return true;
  }
  std::string name() const override { return fs::path(dir_).filename().string(); }

 private:
  std::string dir_;
  std::vector<std::string> files_;
  std::vector<std::optional<cv::Rect2d>> boxes_;  //!< none: the target is not visible (a NaN line)
  size_t i_ = 0;
};

class LogSource : public FrameSource {
 public:
  explicit LogSource(const std::string& path) : path_(path), log_(path, "r") {
    if (!log_.good()) throw std::runtime_error(path + ": cannot open as an LCM log");
  }
  bool next(EvalFrame& out) override {
    // Frames come out in seq order once their ground truth has arrived (either may come first); a frame
    // whose truth never comes is given without one at the end.
    while (true) {
      if (!frames_.empty() && truths_.count(frames_.begin()->first)) return emit(out, true);
      const lcm::LogEvent* ev = log_.readNextEvent();
      if (!ev) break;
      if (ev->channel == "CAMERA") {
        image_t m;
        if (m.decode(ev->data, 0, ev->datalen) < 0) continue;
        cv::Mat img;
        if (!image_to_mat(m, img).empty()) continue;
        if (img.channels() == 1) cv::cvtColor(img, img, cv::COLOR_GRAY2BGR);
        frames_[m.seq] = img.clone();
      } else if (ev->channel == "GROUND_TRUTH") {
        ground_truth_t g;
        if (g.decode(ev->data, 0, ev->datalen) < 0) continue;
        truths_[g.seq] = cv::Rect2d(g.user_box[0], g.user_box[1], g.user_box[2], g.user_box[3]);
      }
    }
    if (frames_.empty()) return false;
    return emit(out, truths_.count(frames_.begin()->first) > 0);
  }
  std::string name() const override { return fs::path(path_).filename().string(); }

 private:
  bool emit(EvalFrame& out, bool has_truth) {
    const auto it = frames_.begin();
    out.image = it->second;
    out.truth = has_truth ? std::optional<cv::Rect2d>(truths_[it->first]) : std::nullopt;
    out.absent = false;
    truths_.erase(it->first);
    frames_.erase(it);
    return true;
  }
  std::string path_;
  lcm::LogFile log_;
  std::map<int64_t, cv::Mat> frames_;
  std::map<int64_t, cv::Rect2d> truths_;
};

#ifdef GPILOT_HAVE_SYNTHETIC
class SyntheticSource : public FrameSource {
 public:
  SyntheticSource(const std::string& scenario, SyntheticTruthBox truth)
      : world_(SyntheticParams{}, Scenario::load(scenario), 1),
        truth_(truth),
        frames_(static_cast<int64_t>(world_.scenario().duration_s() * world_.params().fps)) {}
  bool next(EvalFrame& out) override {
    if (i_ >= frames_) return false;
    const SyntheticFrame f = world_.render(static_cast<double>(i_) / world_.params().fps, i_, std::nullopt);
    out.image = f.bgr;
    out.truth = cv::Rect2d(f.truth.user_box);
    out.absent = false;
    if (truth_ == SyntheticTruthBox::kFace) {
      // The face box where the face shows; turned away, the head has no truth: left out of the scores.
      out.absent = !(f.truth.face_box.area() > 0);
      if (out.absent) out.truth.reset();
      else out.truth = cv::Rect2d(f.truth.face_box);
    }
    ++i_;
    return true;
  }
  std::string name() const override { return "synthetic " + world_.scenario().name(); }

 private:
  SyntheticWorld world_;
  SyntheticTruthBox truth_;
  int64_t frames_;
  int64_t i_ = 0;
};
#endif

}  // namespace

#ifdef GPILOT_HAVE_SYNTHETIC
std::unique_ptr<FrameSource> open_synthetic(const std::string& scenario, SyntheticTruthBox truth) {
  return std::make_unique<SyntheticSource>(scenario, truth);
}
#endif

std::unique_ptr<FrameSource> open_otb(const std::string& dir) { return std::make_unique<OtbSource>(dir); }
std::unique_ptr<FrameSource> open_lcm_log(const std::string& path) { return std::make_unique<LogSource>(path); }

}  // namespace gpilot
