// Scores of the hands stage against keypoint truth, per person and summed over a set of photos.
//   OUT found:   stage kind OUT on a person with an OUT arm; angle error = angle between the stage's vector
//                (hand - p_uc) and (truth wrist - p_uc), p_uc = the STAGE's own shoulder centre
//                (HandsOutput.shoulder_centre); both arms OUT: the nearer angle.
//   FRONT found: stage kind FRONT on a FRONT person; HIGH/LOW right: the stage vector (hand - p_bc) points up
//                (y < 0) exactly when the truth wrist is above the torso centre (FRONT_HIGH). Two FRONT arms:
//                the one whose wrist is nearer the stage's hand pixel.
//   false hand:  stage kind != NONE on a person whose both arms are REST.
//   kind accuracy over scored people (truth OUT/FRONT/REST <-> stage OUT/FRONT/NONE).
//   hand shows skin: on an OUT or FRONT person, a hand of that kind whose square (the stage's hand square, centred
//                a third of the forearm beyond the truth wrist) holds more skin than the stage needs (the
//                stage's own classifier, adapted to this person, before the opening): the most a skin-colour
//                stage can find (a glove, a held object, a colour cast or a greyscale photo shows none).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "hands/hand_method.hpp"
#include "keypoint_truth.hpp"

namespace gpilot {

struct PersonScore {
  bool scored = false;          //!< person truth OUT, FRONT or REST
  HandKind expected = HandKind::None;
  bool kind_right = false;
  bool out_found = false;
  std::optional<double> out_angle_error_deg;
  bool front_found = false;
  std::optional<bool> front_high_low_right;
  bool false_hand = false;
  std::string truth_arm;                     //!< "left"/"right": the arm the truth vector goes to ("" none)
  std::optional<cv::Point2f> truth_vector;   //!< OUT: truth wrist - stage p_uc; FRONT: truth wrist - stage p_bc
  std::optional<int> hand_skin;              //!< OUT/FRONT: skin pixels in the truth hand's square (the most over its arms)
  bool hand_shows_skin = false;              //!< hand_skin above what the stage needs for that square
};

// skin: the stage's classifier as it ran on this person (nullptr: hand_skin not measured).
PersonScore score_person(const PersonKeypointTruth& truth, const HandsOutput& result, const cv::Mat& bgr = {},
                         const SkinClassifier* skin = nullptr, const HandsParams* params = nullptr);
// The truth hand's square: the stage's hand square side, centred a third of the forearm beyond the wrist.
cv::Rect truth_hand_square(const ArmKeypointTruth& arm, int side);

// Angle between two vectors, degrees 0..180 (0 for a zero vector).
double angle_between_deg(cv::Point2f a, cv::Point2f b);
// Median and p-quantile (nearest rank) of a sample; 0 for an empty one.
double median(std::vector<double> v);
double percentile(std::vector<double> v, double p);

// Sums over people.
class HandsScoreboard {
 public:
  void add_read() { ++read_; }
  void add_skipped_not_visible() { ++skipped_not_visible_; }
  void add_image_unreadable() { ++image_unreadable_; }
  // A usable person (keypoints visible): counted by truth class, arms by label.
  void add_truth(const PersonKeypointTruth& truth);
  void add_no_face(PersonTruth t) { ++no_face_[static_cast<int>(t)]; }
  void add_face_found() { ++faces_found_; }
  // A person the stage ran on (a colourless photo counts as run: the stage's NONE is scored).
  void add_run(const PersonKeypointTruth& truth, const HandsOutput& result, const PersonScore& score);

  int64_t read() const { return read_; }
  int64_t scored() const { return scored_; }
  double kind_accuracy() const;

  // context: box mode, file names ... merged into the object.
  nlohmann::json to_json(const nlohmann::json& context) const;
  void print_table(std::FILE* out, const std::string& title) const;

 private:
  int64_t read_ = 0, skipped_not_visible_ = 0, image_unreadable_ = 0, run_ = 0, scored_ = 0, faces_found_ = 0;
  std::array<int64_t, kPersonTruths> persons_{}, no_face_{}, run_by_truth_{}, colourless_{};
  std::array<int64_t, kArmTruths> arms_{};
  int64_t confusion_[3][3] = {};  //!< [expected][stage], order NONE, OUT, FRONT
  int64_t out_skin_ = 0, out_skin_found_ = 0, front_skin_ = 0, front_skin_found_ = 0;
  int64_t skin_measured_ = 0;  //!< OUT/FRONT persons whose truth hand's skin was counted (a skin classifier ran)
  int64_t out_found_ = 0, front_found_ = 0, front_hl_right_ = 0, false_hand_ = 0, kind_right_ = 0;
  std::vector<double> out_angle_err_;
};

}  // namespace gpilot
