// The per-person CSV of gpilot-eval-hands --coco: one line per annotated person (also the skipped ones, with
// their status), truth per arm and person, the box and face given to the stage, the box the stage used (the
// given one, clipped to the image), the stage's kind, hand pixel,
// reference points and vector, the truth vector and the scores.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "hands/hand_detector.hpp"
#include "hands_score.hpp"
#include "keypoint_truth.hpp"

namespace gpilot {

struct PersonCsvRow {
  std::string image;
  int64_t annotation_id = 0;
  std::string box_mode;
  std::string status;  //!< run, skipped_not_visible, no_face, image_unreadable
  std::string note;
  const PersonKeypointTruth* truth = nullptr;  //!< may be null (image unreadable)
  std::optional<cv::Rect2f> box, face;
  const HandsOutput* result = nullptr;          //!< null when the stage did not run
  const PersonScore* score = nullptr;
};

class PersonCsv {
 public:
  // Throws std::runtime_error if the file cannot be written.
  explicit PersonCsv(const std::string& path);
  ~PersonCsv();
  PersonCsv(const PersonCsv&) = delete;
  PersonCsv& operator=(const PersonCsv&) = delete;

  void write(const PersonCsvRow& row);

 private:
  std::FILE* f_ = nullptr;
};

}  // namespace gpilot
