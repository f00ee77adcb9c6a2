#include "occluder.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>

#include <opencv2/imgproc.hpp>

namespace gpilot {

namespace {

class OccludedSource : public FrameSource {
 public:
  // Each occluder's patch is made once (the texture resized to it), not on every frame of every pass.
  OccludedSource(std::unique_ptr<FrameSource> src, std::vector<Occluder> occluders, const cv::Mat& texture)
      : src_(std::move(src)), occluders_(std::move(occluders)) {
    for (const Occluder& o : occluders_) {
      cv::Mat patch(o.rect.size(), CV_8UC3, cv::Scalar::all(128));
      if (!texture.empty()) cv::resize(texture, patch, o.rect.size(), 0, 0, cv::INTER_AREA);
      cv::Mat grey;
      cv::cvtColor(patch, grey, cv::COLOR_BGR2GRAY);  // for a one-channel frame (a monochrome camera's log)
      patches_.push_back({patch, grey});
    }
  }

  bool next(EvalFrame& out) override {
    if (!src_->next(out)) return false;
    ++frame_;
    bool copied = false;
    for (size_t i = 0; i < occluders_.size(); ++i) {
      const Occluder& o = occluders_[i];
      if (frame_ < o.first || (o.last > 0 && frame_ > o.last)) continue;
      const cv::Rect in_frame = o.rect & cv::Rect(0, 0, out.image.cols, out.image.rows);
      if (in_frame.empty()) continue;
      // The frame may be shared with the source's cache: paint a copy.
      if (!copied) out.image = out.image.clone();
      copied = true;
      const cv::Mat& patch = out.image.channels() == 1 ? patches_[i].grey : patches_[i].bgr;
      patch(in_frame - o.rect.tl()).copyTo(out.image(in_frame));
    }
    return true;
  }
  std::string name() const override { return src_->name() + " (occluded)"; }

 private:
  struct Patch {
    cv::Mat bgr, grey;
  };
  std::unique_ptr<FrameSource> src_;
  std::vector<Occluder> occluders_;
  std::vector<Patch> patches_;
  int frame_ = 0;
};

}  // namespace

std::optional<Occluder> parse_occluder(const std::string& spec) {
  Occluder o;
  const auto at = spec.find('@');
  const std::optional<cv::Rect2d> box = parse_box(spec.substr(0, at));
  if (!box) return std::nullopt;
  o.rect = cv::Rect(cvRound(box->x), cvRound(box->y), cvRound(box->width), cvRound(box->height));
  if (o.rect.width <= 0 || o.rect.height <= 0) return std::nullopt;
  if (at != std::string::npos) {
    const std::string frames = spec.substr(at + 1);
    int first = 0, last = 0, used = 0;
    if (std::sscanf(frames.c_str(), "%d-%n", &first, &used) != 1 || used == 0) return std::nullopt;
    if (used < static_cast<int>(frames.size())) {
      int used_last = 0;
      if (std::sscanf(frames.c_str() + used, "%d%n", &last, &used_last) != 1 || used + used_last != static_cast<int>(frames.size()))
        return std::nullopt;
      if (last < first) return std::nullopt;
    }
    if (first < 1) return std::nullopt;
    o.first = first;
    o.last = last;
  }
  return o;
}

std::unique_ptr<FrameSource> occluded(std::unique_ptr<FrameSource> src, std::vector<Occluder> occluders, const cv::Mat& texture) {
  if (!src) throw std::invalid_argument("occluded: no frame source");
  if (!texture.empty() && texture.type() != CV_8UC3) throw std::invalid_argument("occluded: the texture is not a BGR image");
  return std::make_unique<OccludedSource>(std::move(src), std::move(occluders), texture);
}

}  // namespace gpilot
