// The user's body box from their face box: the paper's "preset head-body ratio". The tracker makes the box
// with it (it starts and re-anchors tracks on faces); the hands stage uses the tracker's USER_TRACK box as
// given, and gpilot-eval-hands makes the box the tracker would make from a face.
#pragma once

#include <opencv2/core/types.hpp>

namespace gpilot {

struct BodyProportions {
  double width_in_faces = 2.75;   //!< body box width / face box width
  double height_in_faces = 7.0;   //!< body box height / face box height
  double top_in_faces = 0.25;     //!< body box top above the face box top, in face heights
  //! body box centre right of the face centre, in face widths (the preset: 0; a track fitted to the image
  //! evidence may differ, see services/tracker/body_fit.hpp)
  double centre_in_faces = 0.0;
};

// Centred on the face horizontally (the preset), its top a little above the face top; not clipped.
inline cv::Rect2d body_from_face(const cv::Rect2d& face, const BodyProportions& p) {
  const double w = face.width * p.width_in_faces;
  const double h = face.height * p.height_in_faces;
  const double cx = face.x + face.width / 2 + p.centre_in_faces * face.width;
  return cv::Rect2d(cx - w / 2, face.y - p.top_in_faces * face.height, w, h);
}

// Where a body box puts the face: body_from_face's inverse.
inline cv::Rect2d face_from_body(const cv::Rect2d& body, const BodyProportions& p) {
  const double fw = body.width / p.width_in_faces;
  const double fh = body.height / p.height_in_faces;
  const double cx = body.x + body.width / 2 - p.centre_in_faces * fw;
  return cv::Rect2d(cx - fw / 2, body.y + p.top_in_faces * fh, fw, fh);
}

// The proportions with which body_from_face(face, p) is body: a box given by hand, measured on the face found
// in it. face must have an area.
inline BodyProportions body_proportions_of(const cv::Rect2d& body, const cv::Rect2d& face) {
  BodyProportions p;
  p.width_in_faces = body.width / face.width;
  p.height_in_faces = body.height / face.height;
  p.top_in_faces = (face.y - body.y) / face.height;
  p.centre_in_faces = ((body.x + body.width / 2) - (face.x + face.width / 2)) / face.width;
  return p;
}

// A rectangle given with box `from` (a face with the body box it came with), at the same place in units of the
// box once the box is `to`: the face the tracker's re-check found, published with the next frame, and the last
// face the hands stage was given, on frames without one. r itself when `from` has no area.
inline cv::Rect2d carried_with_box(const cv::Rect2d& r, const cv::Rect2d& from, const cv::Rect2d& to) {
  if (!(from.width > 0 && from.height > 0)) return r;
  const double kx = to.width / from.width, ky = to.height / from.height;
  return cv::Rect2d(to.x + (r.x - from.x) * kx, to.y + (r.y - from.y) * ky, r.width * kx, r.height * ky);
}

}  // namespace gpilot
