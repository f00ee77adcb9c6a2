// Search / track / lost logic of the tracker stage (see user_tracker.hpp).
#include "user_tracker.hpp"

#include <cmath>
#include <stdexcept>

namespace gpilot {

UserTracker::UserTracker(const TrackerParams& params) : p_(params), faces_(params), dsst_(params.dsst) {}

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
  bad_frames_ = 0;
}

void UserTracker::start(const cv::Mat& frame, const cv::Rect2d& box, InitSource source) {
  dsst_.init(frame, box);
  // The first response, on the frame the filter was learnt from, gives the track's starting confidence.
  const DsstEstimate e = dsst_.track(frame);
  out_.status = TrackStatus::kTracking;
  out_.box = e.box;
  out_.confidence = e.psr;
  out_.init = source;
  last_good_box_ = e.box;
  ++out_.track_id;
  bad_frames_ = 0;
}

void UserTracker::search(const cv::Mat& frame) {
  out_.confidence = 0.0;
  if (const auto face = faces_.detect(frame); face && face->body.width >= 2 && face->body.height >= 2)
    start(frame, face->body, InitSource::kFace);
}

TrackOutput UserTracker::process(const cv::Mat& frame) {
  if (frame.empty() || frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3))
    throw std::invalid_argument("UserTracker: frame must be a non-empty CV_8UC1 or CV_8UC3 image");
  if (frame.size() != frame_size_) {
    if (out_.status == TrackStatus::kTracking) reset();
    frame_size_ = frame.size();
  }

  if (pending_box_) {
    // A manual box is tracked on the part of it inside the frame.
    const cv::Rect2d box = *pending_box_ & cv::Rect2d(0, 0, frame.cols, frame.rows);
    pending_box_.reset();
    if (box.width >= 2 && box.height >= 2) {
      start(frame, box, InitSource::kManual);
      return out_;
    }
  }

  if (out_.status != TrackStatus::kTracking) {
    search(frame);
    return out_;
  }

  const DsstEstimate e = dsst_.track(frame);
  out_.box = e.box;
  out_.confidence = e.psr;
  if (e.psr >= p_.lost_psr) {
    bad_frames_ = 0;
    last_good_box_ = e.box;
    dsst_.learn(frame);
  } else if (++bad_frames_ >= p_.lost_frames) {
    // LOST reports the last box seen with good confidence; the search starts with the next frame.
    out_.status = TrackStatus::kLost;
    out_.box = last_good_box_;
  }
  return out_;
}

}  // namespace gpilot
