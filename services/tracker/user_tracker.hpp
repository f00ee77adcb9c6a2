// The tracker stage's core: searches the user's face, then follows the body box with DSST, watches the
// peak-to-sidelobe ratio, declares LOST after lost_frames bad frames and searches again: while LOST the last
// good filter looks for the target where it was (re-detection) and the face is searched near the last box and
// in the whole frame (alternating, within a per-frame budget); after lost_search_frames the last box is
// dropped and only the face search goes on (SEARCHING). A manual box (TRACKER_INIT) starts a track on the
// next frame; a reset goes back to the face search.
// No LCM, no clock: one frame in, one TrackOutput out; the same frames give the same outputs.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "body_fit.hpp"
#include "dsst.hpp"
#include "face_detector.hpp"
#include "pose/person_detector.hpp"
#include "tracker_models.hpp"
#include "tracker_params.hpp"

namespace gpilot {

enum class TrackStatus { kSearching = 0, kTracking = 1, kLost = 2 };
enum class InitSource { kNone = 0, kFace = 1, kManual = 2, kPerson = 3 };
//! Whether the user faces the drone, by the face re-check (user_track_t.facing).
enum class Facing { kUnknown = 0, kToward = 1, kAway = 2 };

//! What the person search (tracker.person) did since construction (HEALTH).
struct PersonSearchCounters {
  int64_t runs = 0;          //!< frames the person detector ran on
  int64_t detections = 0;    //!< people it found (over its score threshold)
  int64_t not_user = 0;      //!< candidates refused as not the remembered user (clothes, size, the filter)
  int64_t started = 0;       //!< tracks started on a new user found by the body alone
  int64_t reacquired = 0;    //!< remembered users taken back
  int64_t region_steps = 0;  //!< LOST runs whose region had to grow again (the search spread over frames)
  int64_t whole_frame = 0;   //!< LOST runs whose region covered the whole frame
};

struct TrackOutput {
  TrackStatus status = TrackStatus::kSearching;
  cv::Rect2d box;           //!< body box, pixels (TRACKING: current; LOST: last good; SEARCHING: empty)
  double confidence = 0.0;  //!< PSR of this frame's translation response (0 while searching)
  InitSource init = InitSource::kNone;
  //! kAway: a face the cascade found on this user before, of a size it finds (away_min_face_px), missed at the
  //! last away_misses re-checks in a row; kToward: found at the last re-check; else kUnknown. From the frame
  //! after the re-check on, like the face.
  Facing facing = Facing::kUnknown;
  int track_id = 0;         //!< +1 per started track; 0 before the first
  //! The face the cascade found (pixels, inside the frame): in THIS frame on the frame a track starts from a
  //! face; in the frame before, moved as the track moved, on the frame after each re-check that found it
  //! (re-anchored or not, manual tracks included); empty on every other frame.
  std::optional<cv::Rect2d> face;
  //! A face the search found in THIS frame and did not start a track on (its body box failed the image
  //! check, body_fit.hpp); kNone on every other frame.
  FaceRefusal refused = FaceRefusal::kNone;
};

class UserTracker {
 public:
  // models: read by load_tracker_models (tracker_models.hpp) where the tracker is built; with
  // tracker.person.enabled its person detector is required (std::invalid_argument without it).
  UserTracker(const TrackerParams& params, TrackerModels models);

  // Asks for a track on box from the next frame on. "" if accepted, else why not (non-finite, < 2 px).
  std::string set_box(const cv::Rect2d& box);
  // Drops the track (and a pending box) and the user's clothes (any face may be the user), and searches again.
  void reset();

  // One frame (CV_8UC3 or CV_8UC1). Throws std::invalid_argument for an unusable frame, without
  // changing the track. A frame of another size than the track's ends the track (search again).
  // track() gives the frame's output; finish() (the same frame, before the next track()) then does the work
  // whose result only the next frames need: the face re-check, about once a second, and its re-anchor (the
  // cascade on the face window and a new filter: 10-20 ms, which before lay between the frame and its
  // USER_TRACK). Its outcome shows from the next frame on: the face found goes out with it, moved as the track
  // moved; a track dropped off the user is LOST there. process() is both, with track()'s output: what the
  // service publishes, so replay and the tools see the same. track() without finish() before it throws
  // std::logic_error.
  TrackOutput process(const cv::Mat& frame);
  const TrackOutput& track(const cv::Mat& frame);
  void finish(const cv::Mat& frame);

  const TrackOutput& last() const { return out_; }
  int bad_frames() const { return bad_frames_; }
  //! Faces refused for this reason since construction (HEALTH).
  int64_t refusals(FaceRefusal why) const { return refusals_[static_cast<size_t>(why)]; }
  //! Faces the re-check found whose torso did not wear the user's clothes (recheck_min_torso_match): not re-anchored on.
  int64_t other_faces() const { return other_faces_; }
  //! Re-checks that found neither the user's face nor their clothes where the box puts them: the track dropped.
  int64_t off_user() const { return off_user_; }
  //! The user's clothes as the track knows them (torso chromaticity; empty: a manual track, no gate).
  const std::vector<float>& user_clothes() const { return torso_colours_; }
  //! LOST frames whose whole-frame scan step was left out: the user's face too small for it (lost_scan_face_growth).
  int64_t scans_skipped() const { return scans_skipped_; }
  //! The ratios of the current track's body box to its face (the preset, or fitted when it started on a face).
  const BodyProportions& track_body() const { return track_body_; }
  //! The person search's counters (all zero with tracker.person off).
  const PersonSearchCounters& person_counters() const { return person_counters_; }
  //! Whether the person detector ran on the last frame.
  bool person_ran() const { return person_ran_; }

 private:
  // A known user re-found on a face below this share of their last face's width: a part of their face, taken
  // at the last face's size.
  static constexpr double kMinRefoundFaceShare = 0.8;
  void start(const cv::Mat& frame, const cv::Rect2d& box, InitSource source, bool new_track = true);
  void found_face(const cv::Mat& frame, const cv::Rect2d& face);
  bool search(const cv::Mat& frame);
  bool search_person(const cv::Mat& frame, bool remembered);
  //! The filter's answer on a candidate body box: its estimate put there (position and the user's scale), one window.
  DsstEstimate filter_on(const cv::Mat& frame, const cv::Rect2d& body);
  void track_frame(const cv::Mat& frame);
  void lost_frame(const cv::Mat& frame);
  void lose(bool model_trusted);
  // Other: a face in other clothes than the user's; OffUser: no user's face, and the torso where the box
  // puts it is not in the user's clothes.
  enum class FaceCheck { Found, Missed, OutOfView, Other, OffUser };
  FaceCheck recheck_face(const cv::Mat& frame);
  FaceCheck measure_first_face(const cv::Mat& frame, bool in_view);
  FaceCheck missed_face(const cv::Mat& frame, FaceCheck users);
  void update_facing(FaceCheck check, double expected_face_width);
  bool wears_users_clothes(const cv::Mat& frame, const cv::Rect2d& face, bool learn = false);
  std::vector<float> torso_seen(const cv::Mat& frame, const cv::Rect2d& face) const;
  void set_user_clothes(const cv::Mat& frame, const cv::Rect2d& face);
  cv::Rect2d body_box(const cv::Rect2d& window) const;
  //! The user's face width as the last good box puts it (its width over the track's face widths).
  double last_face_width() const { return last_good_box_.width / track_body_.width_in_faces; }
  //! The user's face width as the current box puts it (what the re-check looks for).
  double box_face_width() const { return out_.box.width / track_body_.width_in_faces; }

  TrackerParams p_;
  FaceDetector faces_;
  Dsst dsst_;
  std::optional<cv::Rect2d> pending_box_;
  TrackOutput out_;
  cv::Rect2d last_good_box_;
  DsstEstimate last_good_estimate_;  //!< the filter's last estimate with PSR >= redetect_psr (re-detection starts there)
  BodyProportions track_body_;  //!< the track's body box / face ratios (the re-check re-anchors with them)
  bool ratios_from_first_face_ = false;  //!< manual_box_keeps_shape: the re-check's first face sets track_body_
  std::array<int64_t, kFaceRefusals> refusals_{};
  cv::Rect2d box_in_window_{0, 0, 1, 1};  //!< the body box in units of the DSST window (x, y from its corner)
  cv::Size frame_size_;
  int bad_frames_ = 0;
  int frames_since_face_ = 0;
  bool resize_pending_ = false;  //!< the last re-check's resize was cut to face_recheck_max_step: re-check soon
  int face_misses_ = 0;
  int away_misses_ = 0;        //!< re-checks in a row that missed a face of a size the cascade finds (facing)
  bool face_seen_ = false;     //!< the cascade has found this user's face (start or re-check) since they were taken
  int lost_for_ = 0;           //!< frames since the track was lost (LOST, then SEARCHING: user_memory_frames)
  int redetect_hits_ = 0;      //!< LOST frames in a row where the last good filter's PSR was >= redetect_psr
  bool redetect_ok_ = false;   //!< the last good filter may re-find the target (not after a face-miss loss)
  int64_t searches_ = 0;       //!< face searches since the last track, for the full/local alternation
  int64_t other_faces_ = 0;
  int64_t off_user_ = 0;
  int64_t scans_skipped_ = 0;
  std::vector<float> torso_colours_;  //!< the user's torso chromaticity (tracks from a face; empty: no gate)
  //! The torso colours found where the user's face should be at the last re-check that found someone else there
  //! (Other) or no user (OffUser); empty: none since the user was taken.
  std::vector<float> other_clothes_;
  std::optional<double> recheck_psr_;  //!< track() found a re-check due (this frame's PSR): finish() does it
  struct RecheckFace {
    cv::Rect2d face, box;  //!< the face found and the box (as re-anchored) on the re-check's frame
    int track_id = 0;
  };
  std::optional<RecheckFace> recheck_face_;  //!< published with the next frame
  // The person search (tracker.person).
  std::shared_ptr<PersonDetector> persons_;  //!< null: off (shared by copies: the net is stateless between runs)
  PersonSearchCounters person_counters_;
  int64_t person_wait_ = 0;     //!< searching frames left before the detector's next run (every_frames)
  int64_t person_misses_ = 0;   //!< LOST runs without the user since the loss (the region grows with them)
  int64_t scan_region_ = 0;     //!< the whole-frame search's next region (search_region)
  std::optional<cv::Rect2d> held_person_;  //!< a new user's body box on the last run, and runs in a row found
  int held_runs_ = 0;
  bool person_ran_ = false;
  bool have_filter_ = false;    //!< a track has been started: the filter holds a user's model
  cv::Mat bgr_;                 //!< a grey frame converted for the detector
};

}  // namespace gpilot
