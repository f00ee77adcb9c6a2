// The user search of the paper: OpenCV's Haar face cascade (file from opencv-data, a config key, loaded by the
// caller: face_cascade.hpp) on the frame or a shrunk copy, and the body box made from the face box by the head-body ratio.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/objdetect.hpp>

#include "tracker_params.hpp"

namespace gpilot {

struct FaceDetection {
  cv::Rect2d face;  //!< pixels, in the frame given
  cv::Rect2d body;  //!< body box from the head-body ratio, clipped to the frame
  double pixel = 1;  //!< frame pixels a pixel of the searched image (a shrunk copy's > 1, an enlarged one's < 1)
};

// Where the face re-check looks for the face of a body box: 3 face widths wide centred where the ratios put
// the face, from 0.75 face heights above the face top they put there, 2.5 face heights tall (not clipped).
cv::Rect face_recheck_window(const cv::Rect2d& body, const BodyProportions& ratios);
cv::Rect face_recheck_window(const cv::Rect2d& body, const TrackerParams& params);  // the preset ratios

class FaceDetector {
 public:
  // The re-check takes a face only within this factor of the width it expects, larger or smaller: a face twice
  // or half the size is another person's (nearer or further), not this user's after a DSST scale drift.
  static constexpr double kMaxRecheckFaceScale = 2.0;

  // cascade: tracker.face.cascade, read by load_face_cascade (face_cascade.hpp); an empty one throws
  // std::invalid_argument.
  FaceDetector(const TrackerParams& params, cv::CascadeClassifier cascade);

  // The largest face in frame (CV_8UC3 or CV_8UC1), or none. min_face (frame pixels): the caller takes no
  // smaller face, so the enlarged search (face.upscale) looks only for faces from there (none when all its
  // faces are smaller). The search at frame size keeps its smallest windows: the cascade's grouping of
  // neighbouring hits takes them into a face's box (leaving them out made faces 5 % larger).
  std::optional<FaceDetection> detect(const cv::Mat& frame, double min_face = 0);
  // The same, searching only the part of roi inside frame; boxes in frame pixels.
  std::optional<FaceDetection> detect(const cv::Mat& frame, const cv::Rect& roi, double min_face = 0);
  // Every face found, the largest first (ties by position: the order does not depend on the cascade's):
  // a caller that refuses the largest (a face on a poster) can take the next.
  // max_face (frame pixels, 0: none): nor any larger face (the searches whose smallest face is larger do not run).
  std::vector<FaceDetection> detect_all(const cv::Mat& frame, double min_face = 0, double max_face = 0);
  std::vector<FaceDetection> detect_all(const cv::Mat& frame, const cv::Rect& roi, double min_face = 0, double max_face = 0);
  // The face re-check's search of roi for a face of about expected px, only for faces from min_share of it to
  // twice it, at the cascade's pyramid step face.recheck_scale_factor: for an expected face below
  // face.recheck_small_face_px the window enlarged so that it is face.recheck_enlarged_face_px, a large window
  // shrunk to max_search_pixels. No size expected (<= 0): the plain search.
  std::optional<FaceDetection> recheck(const cv::Mat& frame, const cv::Rect& roi, double expected, double min_share);

  // One frame's share of a whole-frame search spread over frames, within face.scan_slice_pixels: the next
  // tiles of the scan (octaves of face sizes, large faces first; each octave's faces min_face_px .. 2.4x that
  // in its shrunk image, in tiles overlapping by that), the largest face of the first tile that has one. The
  // next step goes on after that tile (a face the caller refuses, e.g. one on a poster, does not hold the scan
  // there); a new frame size or restart_scan() (a track started) start the scan over. scan_slice_pixels 0:
  // detect(frame).
  std::optional<FaceDetection> scan_step(const cv::Mat& frame);
  std::vector<FaceDetection> scan_step_all(const cv::Mat& frame);  //!< every face of that tile, the largest first
  // A search of roi (LOST: around the last box) within the same budget: detect_all(frame, roi) when the window
  // and its enlarged copy (face.upscale) are at most scan_slice_pixels together; else the window is scanned
  // like a frame of its own (octaves, tiles), one budget a call, going on where the last call for the same roi
  // stopped (a new roi starts over). Boxes in frame pixels. max_face (frame pixels, 0: none): no larger face.
  std::vector<FaceDetection> window_step_all(const cv::Mat& frame, const cv::Rect& roi, double max_face = 0);
  void restart_scan() { scan_.next = 0; window_.next = 0; }
  //! Tiles in the scan of a frame of this size, and the pixels the last scan_step or window_step searched.
  int scan_tiles(cv::Size frame_size);
  //! The smallest face (frame pixels) the whole-frame scan of a frame of this size looks for.
  double smallest_scan_face(cv::Size frame_size) const;
  double last_step_pixels() const { return last_step_pixels_; }

 private:
  struct ScanJob {
    double shrink;  //!< frame pixels per searched pixel
    cv::Rect tile;  //!< in the shrunk image
    int max_face;   //!< largest face searched, shrunk pixels (0: no bound)
  };
  struct Scan {
    std::vector<ScanJob> jobs;
    cv::Size planned_for;
    size_t next = 0;
  };
  void plan_scan(cv::Size frame_size, Scan& scan) const;
  //! The next jobs of scan on img (the frame or a window of it) within the budget, faces up to max_face (img
  //! pixels, 0: any); boxes in img's pixels.
  std::vector<FaceDetection> step(const cv::Mat& img, Scan& scan, double max_face = 0);
  std::vector<FaceDetection> sorted_of(std::vector<cv::Rect> faces, double k, cv::Point offset, const cv::Mat& frame) const;
  void grey_of(const cv::Mat& img);  //!< img (BGR or grey) into grey_
  //! detect_all with the cascade's pyramid step given (the re-check's finer one).
  std::vector<FaceDetection> detect_all_at(const cv::Mat& frame, double min_face, double max_face, double scale_factor);
  //! The faces of min_px .. max_px in grey_ enlarged u times (into small_), boxes in grey_'s pixels, largest first.
  std::vector<FaceDetection> search_enlarged(double u, int min_px, int max_px, const cv::Mat& img, double scale_factor);
  //! Boxes found in frame(r) moved into frame's pixels, each body box made again there.
  std::vector<FaceDetection> in_frame(std::vector<FaceDetection> all, const cv::Rect& r, const cv::Mat& frame) const;

  TrackerParams p_;
  cv::CascadeClassifier cascade_;
  cv::Mat grey_, small_;
  Scan scan_;    //!< the whole frame's
  Scan window_;  //!< the window's of window_step_all, for window_for_
  cv::Rect window_for_;
  double last_step_pixels_ = 0;
};

}  // namespace gpilot
