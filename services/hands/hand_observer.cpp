#include "hand_observer.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "hands/colour_check.hpp"

namespace gpilot {

HandObserver::HandObserver(const HandsParams& params, const SkinModel& prior)
    : detector_(params, SkinClassifier(prior, params.skin.threshold)), adapter_(params.skin, prior) {}

void HandObserver::reset() {
  adapter_.reset();
  track_id_ = -1;
  last_face_.reset();
}

HandResult HandObserver::observe(const cv::Mat& bgr, const UserView& user) {
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
    adapter_.learn_clothing(bgr, torso_rect(p, g));
  }
  return detector_.detect(bgr, box, &adapter_.classifier(), face_now);
}

}  // namespace gpilot
