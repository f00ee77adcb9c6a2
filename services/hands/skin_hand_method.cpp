#include "skin_hand_method.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "body_proportions.hpp"
#include "hands/colour_check.hpp"

namespace gpilot {

SkinHandMethod::SkinHandMethod(const HandsParams& params, const SkinModel& prior, std::string model_path)
    : detector_(params, SkinClassifier(prior, params.skin.threshold)), adapter_(params.skin, prior),
      clothing_(params.skin.adapt, prior.bins()), model_path_(std::move(model_path)) {}

void SkinHandMethod::reset() {
  adapter_.reset();
  clothing_.reset();
  judged_with_ = nullptr;
  track_id_ = -1;
  last_face_.reset();
}

HandResult SkinHandMethod::detect(const cv::Mat& bgr, const UserView& user) {
  CV_Assert(bgr.type() == CV_8UC3);
  if (user.track_id != track_id_) {
    reset();
    track_id_ = user.track_id;
  }
  const HandsParams& p = detector_.params();
  const bool face = user.face && user.face->width >= 1 && user.face->height >= 1;
  const cv::Rect2f& box = user.box;
  if (!has_colour(bgr, p.skin)) {  // a grey frame teaches the models nothing and can show no skin
    HandResult none;
    none.geometry = hand_geometry(p, box, bgr.size());
    none.colourless = true;
    return none;
  }
  if (face) adapter_.learn_user(bgr, *user.face);
  // The face: given, or the last one carried along with the box (the tracker gives it about once a second).
  const bool box_ok = box.width > 0 && box.height > 0 && std::isfinite(box.x) && std::isfinite(box.y);
  std::optional<cv::Rect2f> face_now;
  if (face) {
    face_now = *user.face;
    if (box_ok) last_face_ = FaceWithBox{*user.face, box};
  } else if (last_face_ && box_ok) {
    face_now = cv::Rect2f(carried_with_box(last_face_->face, last_face_->box, box));
  }
  const HandGeometry g = hand_geometry(p, box, bgr.size(), face_now);
  if (g.valid) {
    const double m = p.skin.adapt.scene_margin * box.width;
    // Clamped before the conversion to int: a box far beyond the image must not overflow it.
    const auto px = [](double v) { return static_cast<int>(std::clamp(v, -1e7, 1e7)); };
    const cv::Rect exclude = cv::Rect(cv::Point(px(std::floor(box.x - m)), px(std::floor(box.y - m))),
                                      cv::Point(px(std::ceil(box.br().x + m)), px(std::ceil(box.br().y)))) &
                             cv::Rect(0, 0, bgr.cols, bgr.rows);
    adapter_.learn_scene(bgr, exclude);
  }
  // Learnt on every frame, an empty torso (an invalid box) leaving nothing worn: the detector reads this frame's.
  clothing_.learn(bgr, g.valid ? torso_rect(p, g) : cv::Rect(), adapter_.user_skin_colours());
  judged_with_ = &adapter_.classifier_for_frame(&clothing_);
  return detector_.detect(bgr, box, judged_with_, face_now, &clothing_);
}

HandsOutput SkinHandMethod::observe(const cv::Mat& bgr, const UserView& user, int64_t /*utime*/) {
  HandResult r;
  if (user.tracking) r = detect(bgr, user);
  else r.geometry = hand_geometry(params(), user.box, bgr.size());
  HandsOutput out;
  out.kind = r.kind;
  out.vector = r.vector;
  out.hand = cv::Point2f(r.hand);
  out.hand_box = r.hand_box;
  out.shoulder_centre = r.geometry.shoulder_centre;
  out.body_centre = r.geometry.body_centre;
  out.user_box = user.box;
  if (r.colourless)
    out.refused = "skin needs colour, the frame has none (a monochrome or infrared camera, or a greyscale video?): fewer "
                  "than hands.skin.min_colour_fraction of its pixels differ in B, G, R by hands.skin.min_chroma";
  const bool detected = user.tracking && !r.colourless;
  out.skin = SkinDiagnostics{r, adaptation(), detected ? last_mask() : cv::Mat(), detected ? last_roi() : cv::Rect(),
                             judged_with_ ? judged_with_ : &detector_.classifier()};
  return out;
}

}  // namespace gpilot
