// Search / track / lost logic of the tracker stage (see user_tracker.hpp).
#include "user_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "box_iou.hpp"

namespace gpilot {
namespace {

constexpr double kDegreesPerRadian = 180.0 / CV_PI;

// The face as the cascade would box it, from the detection's keypoints (person.face_in_body, face_above_shoulders).
cv::Rect2d implied_face(const PersonDetection& d, const PersonSearchParams& p) {
  const cv::Point2d hips(d.keypoints[person_keypoint::kHipCentre]), top(d.keypoints[person_keypoint::kBodyScale]);
  const cv::Point2d shoulders(d.keypoints[person_keypoint::kShoulderCentre]);
  const double w = p.face_in_body * cv::norm(top - hips);
  const cv::Point2d c(shoulders.x, shoulders.y - p.face_above_shoulders * w);
  return cv::Rect2d(c.x - w / 2, c.y - w / 2, w, w);
}

// The whole-frame search's region number k: 0 the frame itself, then squares of tile_share x its short side
// covering it (overlapping by a third of a side at least).
cv::Rect2f search_region(const cv::Size& frame, double tile_share, int64_t k) {
  const double side = tile_share * std::min(frame.width, frame.height);
  const auto count = [&](int length) { return length <= side ? 1 : 1 + static_cast<int>(std::ceil((length - side) / (side * 2 / 3))); };
  const int nx = count(frame.width), ny = count(frame.height);
  const int64_t i = k % (1 + nx * ny);
  if (i == 0 || side >= std::max(frame.width, frame.height)) return {};
  const int tx = static_cast<int>((i - 1) % nx), ty = static_cast<int>((i - 1) / nx);
  const double x = nx > 1 ? tx * (frame.width - side) / (nx - 1) : 0.0, y = ny > 1 ? ty * (frame.height - side) / (ny - 1) : 0.0;
  return cv::Rect2f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(side), static_cast<float>(side));
}

// Upright: the body's axis (hips to the full-body scale point, above them) within max_tilt_deg of vertical; the
// shoulders (and with hips, the hips too) inside the frame.
bool upright_in_view(const PersonDetection& d, const cv::Size& frame, double max_tilt_deg, bool hips) {
  const cv::Rect2f in(0, 0, static_cast<float>(frame.width), static_cast<float>(frame.height));
  const cv::Point2f hip = d.keypoints[person_keypoint::kHipCentre];
  const cv::Point2f top = d.keypoints[person_keypoint::kBodyScale];
  if (!in.contains(d.keypoints[person_keypoint::kShoulderCentre]) || (hips && !in.contains(hip))) return false;
  const cv::Point2f axis = top - hip;
  if (!(axis.y < 0)) return false;
  return std::atan2(std::abs(axis.x), -axis.y) * kDegreesPerRadian <= max_tilt_deg;
}

}  // namespace

namespace {
// A manual box's first face search (measure_first_face): the box grown by this share of its width each side,
// faces up to kMaxFirstFaceInBox box widths.
constexpr double kFirstFaceBoxGrowth = 0.25;
constexpr double kMaxFirstFaceInBox = 1.5;
}  // namespace

UserTracker::UserTracker(const TrackerParams& params, TrackerModels models)
    : p_(params),
      faces_(params, std::move(models.face_cascade)),
      dsst_(params.dsst),
      track_body_(params.body()),
      persons_(params.person.enabled ? std::move(models.persons) : nullptr) {
  if (params.person.enabled && !persons_)
    throw std::invalid_argument("UserTracker: tracker.person.enabled without its detector (load_tracker_models)");
}

std::string UserTracker::set_box(const cv::Rect2d& box) {
  if (!std::isfinite(box.x) || !std::isfinite(box.y) || !std::isfinite(box.width) || !std::isfinite(box.height))
    return "box is not finite";
  if (box.width < 2 || box.height < 2) return "box is smaller than 2x2 pixels";
  pending_box_ = box;
  return "";
}

void UserTracker::reset() {
  pending_box_.reset();
  out_.status = TrackStatus::kSearching;
  out_.box = cv::Rect2d();
  out_.confidence = 0.0;
  out_.init = InitSource::kNone;
  out_.face.reset();
  recheck_psr_.reset();
  recheck_face_.reset();
  resize_pending_ = false;
  ratios_from_first_face_ = false;
  out_.facing = Facing::kUnknown;
  away_misses_ = 0;
  face_seen_ = false;
  bad_frames_ = 0;
  searches_ = 0;
  torso_colours_.clear();  // whoever comes is the user (RESET: a new user)
  other_clothes_.clear();
  faces_.restart_scan();
  held_person_.reset();
  held_runs_ = 0;
  person_misses_ = 0;
  person_wait_ = 0;
  scan_region_ = 0;
}

// DSST follows the part of the body box inside the frame (the window); the body box keeps its place and size
// relative to the window, so it moves and scales with it. A user close to the drone overflows the image: DSST
// on the whole box would learn mostly replicated border, and could not start at all once the box's centre
// is out of the image, which is where a re-check must re-anchor it most.
void UserTracker::start(const cv::Mat& frame, const cv::Rect2d& box, InitSource source, bool new_track) {
  const cv::Rect2d frame_rect(0, 0, frame.cols, frame.rows);
  const bool in_view = (box & frame_rect) == box;
  const cv::Rect2d window = in_view ? box : box & frame_rect;
  box_in_window_ = in_view ? cv::Rect2d(0, 0, 1, 1)
                           : cv::Rect2d((box.x - window.x) / window.width, (box.y - window.y) / window.height,
                                        box.width / window.width, box.height / window.height);
  dsst_.init(frame, window);
  // The first response, on the frame the filter was learnt from, gives the track's starting confidence.
  const DsstEstimate e = dsst_.track(frame);
  out_.status = TrackStatus::kTracking;
  out_.box = body_box(e.box);
  out_.confidence = e.psr;
  out_.init = source;
  if (source != InitSource::kManual) ratios_from_first_face_ = false;  // a face's or a body's track has its ratios
  last_good_box_ = out_.box;
  last_good_estimate_ = dsst_.estimate();
  if (new_track) ++out_.track_id;
  have_filter_ = true;
  held_person_.reset();
  held_runs_ = 0;
  bad_frames_ = 0;
  frames_since_face_ = 0;
  if (new_track) {
    face_misses_ = 0;
    resize_pending_ = false;
    away_misses_ = 0;
    out_.facing = source == InitSource::kFace ? Facing::kToward : Facing::kUnknown;
  }
  if (source == InitSource::kFace) face_seen_ = true;
}

// The face as published: clipped to the frame (a downscaled search can put its edge up to a pixel outside).
void UserTracker::found_face(const cv::Mat& frame, const cv::Rect2d& face) {
  const cv::Rect2d in_frame = face & cv::Rect2d(0, 0, frame.cols, frame.rows);
  if (in_frame.width > 0 && in_frame.height > 0) out_.face = in_frame;
}

cv::Rect2d UserTracker::body_box(const cv::Rect2d& window) const {
  const cv::Rect2d& k = box_in_window_;
  return cv::Rect2d(window.x + k.x * window.width, window.y + k.y * window.height, k.width * window.width,
                    k.height * window.height);
}

// Looks for the face where the box puts it (the box's top, a face-and-a-half around) and, when the body box
// of that face and the tracked box disagree, restarts the filter on the face's box (same track).
UserTracker::FaceCheck UserTracker::recheck_face(const cv::Mat& frame) {
  frames_since_face_ = 0;
  resize_pending_ = false;
  const cv::Rect2d& b = out_.box;
  const double fw = box_face_width();
  const cv::Rect roi = face_recheck_window(b, track_body_);
  const bool in_view = (roi & cv::Rect(0, 0, frame.cols, frame.rows)) == roi;
  if (ratios_from_first_face_) return measure_first_face(frame, in_view);
  // A face below face_recheck_min_share of the expected width is not looked for (a face below half of it would
  // not be this user's: the scale gate below).
  const auto face = faces_.recheck(frame, roi, fw, p_.face_recheck_min_share);
  if (!face) return missed_face(frame, in_view ? FaceCheck::Missed : FaceCheck::OutOfView);
  // Where the box puts the face (the track's own ratios, fitted when it started: not fitted again, the user may be
  // gesturing now) and where the face is: the shift is the face's, not its body box's (a face found 2 px larger
  // puts the centre of the body box made from it 7 px lower, a shift nobody made). The box is not clipped to
  // the frame: a user close to the drone has their feet out of view.
  const cv::Rect2d put = face_from_body(b, track_body_);
  const cv::Point2d put_centre = (put.tl() + put.br()) * 0.5;
  const cv::Point2d face_centre = (face->face.tl() + face->face.br()) * 0.5;
  const double scale = std::abs(std::log(face->face.width / fw));
  const cv::Point2d shift = face_centre - put_centre;
  if (scale > std::log(FaceDetector::kMaxRecheckFaceScale)) return missed_face(frame, FaceCheck::Missed);  // not this user's face
  // Nor is one whose torso wears other clothes (a look-alike crossing in front or standing beside).
  if (!wears_users_clothes(frame, face->face, true)) {
    other_clothes_ = torso_seen(frame, face->face);
    ++other_faces_;
    return FaceCheck::Other;
  }
  // A manual track learns the user's clothes from the first face its re-check finds (a face's or a body's track
  // has them from its start): from then on a walker in other clothes is not taken for the user.
  if (out_.init == InitSource::kManual && torso_colours_.empty()) set_user_clothes(frame, face->face);
  // The face's size is taken only where it differs from the box's by more than the tolerance: the cascade finds a
  // far user's 15 px face a pyramid step (10 %) larger or smaller from one re-check to the next, and a re-anchor
  // for a shift alone that took it too made a 58 px box 66 px for seconds (open loop `far`). A shift alone moves
  // the box and keeps its size; a resize keeps the box's shape (the track's ratios), scaled about the face.
  const bool resize = scale > std::log1p(p_.face_recheck_tolerance) &&
                      std::abs(face->face.width - fw) > p_.face_recheck_tolerance_px * face->pixel;
  if (resize || std::hypot(shift.x, shift.y) > p_.face_recheck_tolerance * b.width) {
    double k = resize ? face->face.width / fw : 1.0;
    const double step = 1.0 + p_.face_recheck_max_step;
    if (p_.face_recheck_max_step > 0 && (k > step || k < 1.0 / step)) {
      k = std::clamp(k, 1.0 / step, step);
      resize_pending_ = true;  // the rest, if the next re-check still finds it
    }
    start(frame,
          cv::Rect2d(face_centre.x - k * (put_centre.x - b.x), face_centre.y - k * (put_centre.y - b.y), k * b.width,
                     k * b.height),
          out_.init, false);
  }
  found_face(frame, face->face);
  return FaceCheck::Found;
}

// manual_box_keeps_shape: the first face found in a box given by hand sets the track's ratios, and the box keeps
// its shape and place on the user (an annotation wider than the preset, or of the head alone). Where the face is
// in the box is not known yet (a body's box has it at its top, a head's box is all face, a third of the size the
// preset's re-check looks for): the box, grown by a quarter of its width, is searched for faces from
// face_recheck_min_share of the preset's face to kMaxFirstFaceInBox of the box's width (a cascade's face box can
// be wider than a head's annotated box), the largest centred in the box taken. The
// re-check's own search, in the window those ratios put it, then measures it as every later re-check will (a
// plain search's face came a pyramid step off theirs, and each of them resized the box).
UserTracker::FaceCheck UserTracker::measure_first_face(const cv::Mat& frame, bool in_view) {
  const cv::Rect2d& b = out_.box;
  const double grow = kFirstFaceBoxGrowth * b.width;
  const cv::Rect roi(cv::Rect2d(b.x - grow, b.y - grow, b.width + 2 * grow, b.height + 2 * grow));
  std::optional<cv::Rect2d> face;
  const double min_face = p_.face_recheck_min_share * box_face_width();
  for (const FaceDetection& f : faces_.detect_all(frame, roi, min_face, kMaxFirstFaceInBox * b.width))
    if (b.contains((f.face.tl() + f.face.br()) * 0.5)) {
      face = f.face;
      break;
    }
  if (!face) return missed_face(frame, in_view ? FaceCheck::Missed : FaceCheck::OutOfView);
  BodyProportions measured = body_proportions_of(b, *face);
  const auto again =
      faces_.recheck(frame, face_recheck_window(b, measured), face->width, p_.face_recheck_min_share);
  const double max_scale = std::log(FaceDetector::kMaxRecheckFaceScale);
  if (again && std::abs(std::log(again->face.width / face->width)) <= max_scale) {
    face = again->face;
    measured = body_proportions_of(b, *face);
  }
  ratios_from_first_face_ = false;
  track_body_ = measured;
  if (torso_colours_.empty()) set_user_clothes(frame, *face);  // the manual track's clothes (recheck_face)
  found_face(frame, *face);
  return FaceCheck::Found;
}

// No face of the user's size where the box puts it. The user may have turned away, or the box slid off them:
// onto a look-alike who crossed in front (their face, nearer, twice the size) and then onto the background,
// at a PSR that stayed well above face_miss_psr (scenario bystander: 40 s on a wall, flown on), or held the
// image's edge after a user who walked out of view. The torso where the box puts it (the part in view) tells
// which: the user's clothes, `users` (a miss, or out of view); other colours, the box is not on the user.
UserTracker::FaceCheck UserTracker::missed_face(const cv::Mat& frame, FaceCheck users) {
  const cv::Rect2d face = face_from_body(out_.box, track_body_);
  if (wears_users_clothes(frame, face)) return users;
  other_clothes_ = torso_seen(frame, face);
  ++off_user_;
  return FaceCheck::OffUser;
}

// Turned away or not, by the re-check. Only a face the cascade has found on this user before, and of a size it
// finds (away_min_face_px), is missed: a far user, or one whose face it never found (masked, in poor light,
// started by the body), is kUnknown, not kAway.
void UserTracker::update_facing(FaceCheck check, double expected_face_width) {
  if (check == FaceCheck::Found) {
    face_seen_ = true;
    away_misses_ = 0;
    out_.facing = Facing::kToward;
  } else if (check == FaceCheck::Missed) {
    if (p_.away_misses > 0 && face_seen_ && expected_face_width >= p_.away_min_face_px) {
      if (++away_misses_ >= p_.away_misses) out_.facing = Facing::kAway;
    } else {
      away_misses_ = 0;
      out_.facing = Facing::kUnknown;
    }
  }  // out of view: neither; Other, OffUser: the track is lost
}

std::vector<float> UserTracker::torso_seen(const cv::Mat& frame, const cv::Rect2d& face) const {
  return torso_colours(frame, face, p_.body_fit, p_.torso_colour_bins, p_.torso_dark_level);
}

// A new user: their clothes are the torso's under their face; nobody else's known yet.
void UserTracker::set_user_clothes(const cv::Mat& frame, const cv::Rect2d& face) {
  torso_colours_ = torso_seen(frame, face);
  other_clothes_.clear();
}

// Whether the torso under a face wears the track's clothes (recheck_min_torso_match); true when there is
// nothing to compare (the gate off, a manual track, a grey frame, no torso in view). learn: blend a matching
// torso's colours into the track's.
bool UserTracker::wears_users_clothes(const cv::Mat& frame, const cv::Rect2d& face, bool learn) {
  if (p_.recheck_min_torso_match <= 0 || torso_colours_.empty()) return true;
  const std::vector<float> seen = torso_seen(frame, face);
  const double match = colour_match(torso_colours_, seen);
  if (match < 0) return true;
  if (match < p_.recheck_min_torso_match) return false;
  // A torso more like the clothes last found where the user's should be (Other, OffUser) than the user's: that
  // person again, over part of the user (recheck_other_clothes).
  if (p_.recheck_other_clothes && !other_clothes_.empty() && colour_match(other_clothes_, seen) > match) return false;
  if (learn)
    for (size_t i = 0; i < seen.size(); ++i)
      torso_colours_[i] += static_cast<float>(p_.torso_colour_rate) * (seen[i] - torso_colours_[i]);
  return true;
}

// One face search within the per-frame budget: SEARCHING, a step of the whole-frame scan (FaceDetector::
// scan_step, face.scan_slice_pixels a frame); LOST, every search_full_stride-th frame a scan step, the others
// the last good box grown by search_local_scale, within the same budget (window_step_all: a window over it is
// searched over frames). True when a track started.
bool UserTracker::search(const cv::Mat& frame) {
  out_.confidence = 0.0;
  const bool full = out_.status != TrackStatus::kLost || searches_++ % p_.search_full_stride == 0;
  std::vector<FaceDetection> faces;
  // A LOST user whose face the scan cannot find even grown by lost_scan_face_growth (a far person): not scanned for.
  const bool findable = out_.status != TrackStatus::kLost || p_.lost_scan_face_growth <= 0 ||
                        p_.lost_scan_face_growth * last_face_width() >= faces_.smallest_scan_face(frame.size());
  if (full && !findable) {
    ++scans_skipped_;
  } else if (full) {
    faces = faces_.scan_step_all(frame);
  } else {
    const cv::Rect2d& b = last_good_box_;
    const double g = p_.search_local_scale;
    const cv::Point2d c = (b.tl() + b.br()) * 0.5;
    // Around the last box, faces up to the last one grown by lost_scan_face_growth (the re-check's scale gate: a
    // larger one is not the user's; the whole-frame scan, which runs for such a size, looks for any).
    const double max_face = p_.lost_scan_face_growth > 0 ? p_.lost_scan_face_growth * last_face_width() : 0.0;
    faces = faces_.window_step_all(frame, cv::Rect(cv::Rect2d(c.x - g * b.width / 2, c.y - g * b.height / 2, g * b.width, g * b.height)),
                                   max_face);
  }
  // Each face's body box is checked against the image before a track starts on it (body_fit.hpp), the
  // largest face first: a face with no body in view under it (on a poster, at the bottom edge) is refused
  // (counted) and the next one tried; else the box is fitted to the person.
  // While LOST the user is known: a face in other clothes is someone else's (a look-alike who walked in front
  // took the track with them). Once SEARCHING, the box dropped, still for user_memory_frames; then any face may
  // be the user. Known, their build is too (below).
  const bool remembered = out_.status == TrackStatus::kLost || lost_for_ < p_.lost_search_frames + p_.user_memory_frames;
  const bool known = remembered && !torso_colours_.empty();
  for (const FaceDetection& face : faces) {
    if (remembered && !wears_users_clothes(frame, face.face)) {
      ++other_faces_;
      continue;
    }
    const BodyFit fit = fit_body(frame, face.face, p_.body(), p_.body_fit);
    if (fit.refused != FaceRefusal::kNone) {
      ++refusals_[static_cast<size_t>(fit.refused)];
      if (out_.refused == FaceRefusal::kNone) out_.refused = fit.refused;
      continue;
    }
    // The whole body box, as the re-check makes it: the part in view, which holds the face, is what DSST follows.
    // The user known (their clothes matched): the last track's ratios, not a new fit on a body someone may half
    // hide (a walker in front narrowed a re-found user's box from 86 to 45 px, and the hands stage then misread
    // their arms for the rest of the run).
    // A face much smaller than the user's last one is a part of it (the scan's pyramid found a 22 px face inside
    // the re-found user's 36 px one in a CI bystander run: a 62 px box for their 90, and the hands stage read a
    // resting hand as CLOSER until the next re-check): taken at the last face's size, which that re-check, a
    // second later, corrects if the user did move away.
    if (known) {
      cv::Rect2d user_face = face.face;
      const double last_face = last_face_width();
      if (user_face.width < kMinRefoundFaceShare * last_face) {
        const cv::Point2d c = (user_face.tl() + user_face.br()) * 0.5;
        user_face = cv::Rect2d(c.x - last_face / 2, c.y - last_face / 2, last_face, last_face);
      }
      start(frame, body_from_face(user_face, track_body_), InitSource::kFace);
    } else {
      track_body_ = fit.body;
      start(frame, fit.box, InitSource::kFace);
    }
    // A known user's clothes are blended with what their torso shows now, as a re-check blends them, not replaced
    // by it: re-found with a walker's shirt still over part of the torso (a match of 0.62 in a CI bystander run,
    // above the gate), the replaced colours matched the user's own shirt 0.45 once the walker had gone, the next
    // re-check took their face for someone else's, and the search refused them for user_memory_frames (10 s).
    if (known)
      wears_users_clothes(frame, face.face, true);
    else
      set_user_clothes(frame, face.face);
    found_face(frame, face.face);
    faces_.restart_scan();  // the next search (after a loss) scans from the first tile
    return true;
  }
  return search_person(frame, remembered);
}

// The body box's DSST window (body_box's inverse, the track's box_in_window_).
DsstEstimate UserTracker::filter_on(const cv::Mat& frame, const cv::Rect2d& body) {
  const cv::Rect2d& k = box_in_window_;
  const double ww = body.width / k.width, wh = body.height / k.height;
  DsstEstimate at = last_good_estimate_;
  at.box = cv::Rect2d(body.x - k.x * ww, body.y - k.y * wh, ww, wh);
  at.scale = last_good_estimate_.scale * ww / last_good_estimate_.box.width;
  dsst_.restore(at);
  return dsst_.track(frame, false);
}

// The person search (tracker.person): BlazePose's person detector on one searching frame in every_frames.
// A remembered user (LOST, or SEARCHING within user_memory_frames with their clothes known) is taken back by a
// candidate in their clothes, of their size, and (LOST) that the last good filter answers on with accept_psr:
// the filter's box is the new track's. Nobody remembered: a person upright and whole in view, found by
// start_detections runs in a row, starts a track as a face would (body_fit). True when a track started.
bool UserTracker::search_person(const cv::Mat& frame, bool remembered) {
  if (!persons_) return false;
  if (person_wait_ > 0) {
    --person_wait_;
    return false;
  }
  const PersonSearchParams& pp = p_.person;
  person_wait_ = pp.every_frames - 1;
  const bool lost = out_.status == TrackStatus::kLost;
  const bool known = remembered && !torso_colours_.empty();
  const cv::Rect2d frame_rect(0, 0, frame.cols, frame.rows);
  const auto grown = [&](const cv::Rect2d& b, double g) {
    return cv::Rect2d(b.x - g * b.height, b.y - g * b.height, b.width + 2 * g * b.height, b.height + 2 * g * b.height) & frame_rect;
  };
  // Where this run looks (empty: the whole frame): the search spreads over runs.
  cv::Rect2d region = lost ? grown(last_good_box_, pp.region_growth + pp.region_growth_step * static_cast<double>(person_misses_))
                           : held_person_ ? grown(*held_person_, pp.region_growth) : frame_rect;
  if (lost && person_misses_ > 0) ++person_counters_.region_steps;
  if (region == frame_rect) {
    // The whole frame, then its tiles in turn (a far person is too small in the frame letterboxed to 224 px).
    ++person_counters_.whole_frame;
    region = search_region(frame.size(), pp.tile_share, scan_region_++);
  }
  if (frame.channels() == 1) cv::cvtColor(frame, bgr_, cv::COLOR_GRAY2BGR);
  std::vector<PersonDetection> found = persons_->detect(frame.channels() == 3 ? frame : bgr_, cv::Rect2f(region));
  ++person_counters_.runs;
  person_ran_ = true;
  person_counters_.detections += static_cast<int64_t>(found.size());
  if (found.size() > static_cast<size_t>(pp.max_candidates)) found.resize(static_cast<size_t>(pp.max_candidates));

  if (lost || known) {
    struct Candidate {
      double psr;
      cv::Rect2d body, face;
    };
    std::optional<Candidate> best;
    const double last_face = last_face_width();
    for (const PersonDetection& d : found) {
      if (!upright_in_view(d, frame.size(), pp.max_tilt_deg, false)) continue;
      const cv::Rect2d face = implied_face(d, pp);
      if (std::abs(std::log(face.width / last_face)) > std::log(pp.max_size_change) || !wears_users_clothes(frame, face)) {
        ++person_counters_.not_user;
        continue;
      }
      Candidate c{0.0, body_from_face(face, track_body_), face};
      if (lost && have_filter_) {
        const DsstEstimate e = filter_on(frame, c.body);
        if (!(e.psr >= pp.accept_psr)) {
          ++person_counters_.not_user;
          continue;
        }
        c.psr = e.psr;
        c.body = body_box(e.box);
      }
      if (!best || c.psr > best->psr) best = c;
    }
    if (!best) {
      if (lost) ++person_misses_;
      return false;
    }
    start(frame, best->body, InitSource::kPerson);
    if (known) wears_users_clothes(frame, best->face, true);
    ++person_counters_.reacquired;
    person_misses_ = 0;
    faces_.restart_scan();
    return true;
  }

  // Nobody remembered: the same upright person, whole in view, on start_detections runs in a row.
  const PersonDetection* pick = nullptr;
  double pick_iou = -1.0;
  for (const PersonDetection& d : found) {
    if (!upright_in_view(d, frame.size(), pp.max_tilt_deg, true)) continue;
    const double o = held_person_ ? iou(*held_person_, body_from_face(implied_face(d, pp), p_.body())) : 0.0;
    if (o > pick_iou) pick = &d, pick_iou = o;
  }
  if (!pick) {
    held_person_.reset();
    held_runs_ = 0;
    return false;
  }
  const cv::Rect2d face = implied_face(*pick, pp);
  held_runs_ = held_person_ && pick_iou >= pp.start_min_iou ? held_runs_ + 1 : 1;
  held_person_ = body_from_face(face, p_.body());
  if (held_runs_ < pp.start_detections) return false;
  const BodyFit fit = fit_body(frame, face, p_.body(), p_.body_fit);
  if (fit.refused != FaceRefusal::kNone) {
    ++refusals_[static_cast<size_t>(fit.refused)];
    if (out_.refused == FaceRefusal::kNone) out_.refused = fit.refused;
    return false;
  }
  track_body_ = fit.body;
  start(frame, fit.box, InitSource::kPerson);
  set_user_clothes(frame, face);
  face_seen_ = false;  // a new user, by the body: whether the cascade finds their face is not known yet
  ++person_counters_.started;
  person_misses_ = 0;
  faces_.restart_scan();
  return true;
}

void UserTracker::lose(bool model_trusted) {
  // LOST reports the last box seen with good confidence.
  out_.status = TrackStatus::kLost;
  out_.box = last_good_box_;
  face_misses_ = 0;
  lost_for_ = 0;
  redetect_hits_ = 0;
  redetect_ok_ = model_trusted;
  searches_ = 0;
  faces_.restart_scan();
  person_misses_ = 0;
  person_wait_ = 0;
  scan_region_ = 0;
}

void UserTracker::track_frame(const cv::Mat& frame) {
  const DsstEstimate e = dsst_.track(frame);
  out_.box = body_box(e.box);
  out_.confidence = e.psr;
  if (e.psr >= p_.learn_psr) dsst_.learn(frame);
  if (e.psr < p_.lost_psr) {
    if (++bad_frames_ >= p_.lost_frames) lose(true);  // the search starts with the next frame
    return;
  }
  bad_frames_ = 0;
  last_good_box_ = out_.box;
  // Re-detection starts from the last estimate the filter was sure of (a frame above lost_psr can still be
  // one of an occluder's, drifting).
  if (e.psr >= p_.redetect_psr) last_good_estimate_ = dsst_.estimate();
  // A weak frame of a track that knows the user's clothes is re-checked early (someone may be passing in front:
  // the filter, still learning above learn_psr, follows them off within a few frames).
  // So is a box whose face is not wholly in view: a user walking out of the image's side left the box on the
  // edge strip, where the filter then learnt the wall (PSR rising from 11 to 30 in a second).
  const cv::Rect2d face = face_from_body(out_.box, track_body_);
  const bool at_edge = (face & cv::Rect2d(0, 0, frame.cols, frame.rows)) != face;
  const bool weak = (e.psr < p_.weak_recheck_psr || at_edge) && !torso_colours_.empty() && p_.recheck_min_torso_match > 0;
  // A user whose face was just missed is looked at again soon: turned away, or back toward the drone.
  const bool soon = weak || resize_pending_ || away_misses_ > 0;
  ++frames_since_face_;
  if (p_.face_recheck_frames > 0 &&
      (frames_since_face_ >= p_.face_recheck_frames || (soon && frames_since_face_ >= p_.weak_recheck_frames)))
    recheck_psr_ = e.psr;  // finish() re-checks this frame's face, after its output is out
}

void UserTracker::finish(const cv::Mat& frame) {
  if (!recheck_psr_) return;
  const double psr = *recheck_psr_;
  recheck_psr_.reset();
  if (out_.status != TrackStatus::kTracking || frame.size() != frame_size_) return;
  // A face the window cannot fully see (at the image's edge) is neither found nor missed; a miss on a
  // frame where the filter is sure of itself is no evidence of loss (the face can be turned away).
  const double expected_face_width = box_face_width();  // before a re-anchor may change the box
  const FaceCheck check = recheck_face(frame);
  update_facing(check, expected_face_width);
  if (out_.face) {
    // Published with the next frame, moved as the track moves from this one (the box as re-anchored) to it.
    recheck_face_ = RecheckFace{*out_.face, out_.box, out_.track_id};
    out_.face.reset();
  }
  if (check == FaceCheck::Other || check == FaceCheck::OffUser) {
    // Where the box puts the face there is someone else's (other clothes), or no face and not the user's
    // clothes: the box is on someone else or the background, or someone stands in front of the user. Not
    // flown on; the search (which refuses other clothes while LOST) finds the user.
    lose(false);
    return;
  }
  if (check == FaceCheck::Found || (check == FaceCheck::Missed && psr >= p_.face_miss_psr)) face_misses_ = 0;
  if (check == FaceCheck::Missed && psr < p_.face_miss_psr) ++face_misses_;
  if (out_.init == InitSource::kFace && p_.face_recheck_misses > 0 && face_misses_ >= p_.face_recheck_misses)
    lose(false);  // searched again from the next frame
}

void UserTracker::lost_frame(const cv::Mat& frame) {
  ++lost_for_;
  if (redetect_ok_ && p_.redetect_psr > 0) {
    // The last good model, not learnt while lost, searching around the last good estimate on every frame (a
    // search that followed its own peaks would wander off with the background and shrink the scale away).
    dsst_.restore(last_good_estimate_);
    // One window, not the wide search (a weak response is the rule here): the LOST frame's budget is the face search's.
    const DsstEstimate e = dsst_.track(frame, false);
    redetect_hits_ = e.psr >= p_.redetect_psr ? redetect_hits_ + 1 : 0;
    if (redetect_hits_ >= p_.redetect_frames) {
      out_.status = TrackStatus::kTracking;
      out_.box = body_box(e.box);
      out_.confidence = e.psr;
      last_good_box_ = out_.box;
      last_good_estimate_ = dsst_.estimate();
      ++out_.track_id;  // a re-acquisition is a new track (decide's commands name the track)
      bad_frames_ = 0;
      frames_since_face_ = 0;
      face_misses_ = 0;
      dsst_.learn(frame);
      return;
    }
  }
  if (search(frame)) return;
  if (lost_for_ >= p_.lost_search_frames) {
    // The last box is too old to search near or to re-detect from: the face search alone, on the whole frame.
    out_.status = TrackStatus::kSearching;
    out_.box = cv::Rect2d();
    out_.facing = Facing::kUnknown;
    searches_ = 0;
  }
}

TrackOutput UserTracker::process(const cv::Mat& frame) {
  TrackOutput out = track(frame);
  finish(frame);
  return out;
}

const TrackOutput& UserTracker::track(const cv::Mat& frame) {
  if (frame.empty() || frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3))
    throw std::invalid_argument("UserTracker: frame must be a non-empty CV_8UC1 or CV_8UC3 image");
  if (recheck_psr_) throw std::logic_error("UserTracker::track: finish() was not called on the last frame");
  out_.face.reset();  // set again below only if the cascade finds the face in this frame
  out_.refused = FaceRefusal::kNone;
  person_ran_ = false;
  std::optional<RecheckFace> rechecked;
  rechecked.swap(recheck_face_);
  if (frame.size() != frame_size_) {
    if (out_.status != TrackStatus::kSearching) reset();  // a LOST track's filter and box are of the old size too
    frame_size_ = frame.size();
  }

  if (pending_box_) {
    // A manual box is tracked on the part of it inside the frame.
    const cv::Rect2d box = *pending_box_ & cv::Rect2d(0, 0, frame.cols, frame.rows);
    pending_box_.reset();
    if (box.width >= 2 && box.height >= 2) {
      track_body_ = p_.body();  // where a manual box puts the face, at least until the re-check finds it
      ratios_from_first_face_ = p_.manual_box_keeps_shape;
      face_seen_ = false;
      torso_colours_.clear();   // its clothes: learnt when the re-check first finds the face, ungated until then
      other_clothes_.clear();
      start(frame, box, InitSource::kManual);
      return out_;
    }
  }

  switch (out_.status) {
    case TrackStatus::kTracking:
      track_frame(frame);
      // The last frame's re-check found the face: it goes out now, where the track moved it.
      if (rechecked && out_.status == TrackStatus::kTracking && out_.track_id == rechecked->track_id && !out_.face)
        found_face(frame, carried_with_box(rechecked->face, rechecked->box, out_.box));
      break;
    case TrackStatus::kLost: lost_frame(frame); break;
    case TrackStatus::kSearching:
      search(frame);
      // user_memory_frames counts on from lost_search_frames (held there: a search may last for days)
      lost_for_ = std::min(lost_for_ + 1, p_.lost_search_frames + p_.user_memory_frames);
      break;
  }
  return out_;
}

}  // namespace gpilot
