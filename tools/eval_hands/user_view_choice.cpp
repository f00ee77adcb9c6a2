#include "user_view_choice.hpp"

#include "face_cascade.hpp"

namespace gpilot {

namespace {

cv::Rect2f grown(const cv::Rect2f& r, float factor) {
  const float w = r.width * factor, h = r.height * factor;
  return {r.x + r.width / 2 - w / 2, r.y + r.height / 2 - h / 2, w, h};
}

cv::Rect to_pixels(const cv::Rect2f& r, cv::Size image) {
  const cv::Rect px(cv::Point(cvFloor(r.x), cvFloor(r.y)), cv::Point(cvCeil(r.x + r.width), cvCeil(r.y + r.height)));
  return px & cv::Rect(0, 0, image.width, image.height);
}

cv::Rect2f to_float(const cv::Rect2d& r) {
  return {static_cast<float>(r.x), static_cast<float>(r.y), static_cast<float>(r.width), static_cast<float>(r.height)};
}

}  // namespace

const char* box_mode_name(BoxMode m) {
  switch (m) {
    case BoxMode::Annotation: return "annotation";
    case BoxMode::Face: return "face";
    default: return "keypoints";
  }
}

UserViewChooser::UserViewChooser(const TrackerParams& tracker, BoxMode mode) : tracker_(tracker), mode_(mode), faces_(tracker, load_face_cascade(tracker)) {}

ChosenView UserViewChooser::choose(const cv::Mat& bgr, const cv::Rect2f& annotation_box, const PersonKeypointTruth& truth,
                                   int32_t track_id) {
  ChosenView c;
  const cv::Rect image(0, 0, bgr.cols, bgr.rows);
  if (mode_ == BoxMode::Annotation) {
    c.search_window = face_recheck_window(cv::Rect2d(annotation_box), tracker_) & image;
    // As the tracker: a face found makes the body box (its re-check re-anchors the box on the face it finds).
    const auto f = faces_.detect(bgr, c.search_window);
    if (f) c.face = to_float(f->face);
    else c.note = "no face in the re-check window";
    c.view = UserView{f ? to_float(body_from_face(f->face, tracker_.body())) : annotation_box, c.face, track_id};
    return c;
  }
  if (!truth.face_box) {
    c.note = "no face keypoints";
    return c;
  }
  if (mode_ == BoxMode::Keypoints) {
    c.face = *truth.face_box;
    c.search_window = to_pixels(*truth.face_box, bgr.size());
    c.view = UserView{to_float(body_from_face(cv::Rect2d(*truth.face_box), tracker_.body())), c.face, track_id};
    return c;
  }
  c.search_window = to_pixels(grown(*truth.face_box, 2.0f), bgr.size());
  const auto f = faces_.detect(bgr, c.search_window);
  if (!f) {
    c.note = "no face in the head region";
    return c;
  }
  const cv::Rect2f face = to_float(f->face);
  const cv::Point2f centre(face.x + face.width / 2, face.y + face.height / 2);
  if (!grown(*truth.face_box, 1.5f).contains(centre)) {
    c.note = "face found off the head keypoints";
    return c;
  }
  c.face = face;
  c.view = UserView{to_float(body_from_face(f->face, tracker_.body())), face, track_id};
  return c;
}

}  // namespace gpilot
