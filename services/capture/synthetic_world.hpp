// The synthetic world: a person who gestures, standing in front of a photograph, seen by the drone's camera.
// A pure core (no LCM, no clock): render(t, frame_index, camera) is a function of its arguments, the params,
// the scenario and the seed, so the same inputs give byte-identical frames.
//
// API (library target gpilot_capture_core; headers in services/capture/):
//   Scenario sc = Scenario::load("tour");        // deploy/scenarios/tour.yaml, or any path to a .yaml
//   SyntheticWorld world(config.section<CaptureParams>("capture").synthetic, sc, /*seed=*/1);
//   SyntheticFrame f = world.render(t_s, frame_index, std::nullopt);        // the scenario's fixed camera
//   SyntheticFrame g = world.render(t_s, frame_index, CameraPose{n, e, d, yaw});  // closed loop: the vehicle
//   f.bgr: CV_8UC3 frame (params.width x params.height); f.truth: ground truth in image pixels.
//
// Geometry. World NED (metres); the person stands at scenario person.north/east on the ground (down = 0)
// and turns to face the camera wherever it is (the paper's assumption), unless the scenario fixes
// person.facing_yaw_deg. The camera is a pinhole at CameraPose with
// its optical axis level along yaw (0 = north, clockwise positive); fx = fy = (width/2) / tan(hfov/2), principal
// point at the image centre. The person faces the camera, so their right hand appears on the image's LEFT.
//
// Ground truth (SyntheticTruth, all image pixels, the semantics of lcmtypes/ground_truth_t.lcm):
// - face_box: where the Haar cascade finds the pasted face (measured once on the portrait: its box there is
//   97 x 97 px at (177, 66) of astronaut.png), projected; bounding box of the projected corners.
// - user_box: the body box of face_box with the preset head-body ratios (body_from_face, BodyProportions: the
//   paper's preset; the tracker's defaults) — by definition the box a perfect tracker reports. The person's
//   proportions (person_figure.hpp) put torso, resting arms and hands inside it and a stretched-out hand well
//   outside it.
// - shoulder_centre, body_centre: the paper's p_uc and p_bc from user_box with the truth's own ratios
//   (gesture_truth.hpp, truth_rules; the hands stage's defaults), the points a vector is measured from.
// - left_hand, right_hand: projected centres of the person's own left/right hand; hand_size: side of a square
//   centred there that holds the whole hand.
// - gesture: the scenario's intended gesture (ground_truth_t::GESTURE_*); during a transition it switches to
//   the next keyframe's gesture half-way.
// - left_elbow, right_elbow, left_wrist, right_wrist: projected joints of the arms (for tests and tools; the
//   LCM message does not carry them).
//
// Scene. Back to front: the background photo (graded as the scenario says), the scenario's wall if any (a
// textured plane in the world, per-pixel ray intersection, labelled Wall), the distractor (behind the wall
// when it is further than the wall), the person and the scenario's bystanders (the same figure and face, their
// own clothes, each facing the camera; all people drawn far to near, so one who walks between the user and
// the camera hides the user; labelled Bystander), then the frame-wide nuisances. The truth stays the user's:
// a bystander in front of the user does not change the user's boxes.
// - expected_kind / expected_vector / expected_mode / expected_direction: the paper's Alg. 1/2/3 applied to the
//   true hands and the true user box (gesture_truth.hpp lists the simplifications).
// - a person behind the camera is not drawn; the boxes, points and hand_size are then 0 and the expected
//   kind/mode NONE/HOVER.
// - person_position: NED of the point between the feet (sideways step included); camera: the pose rendered
//   from (the vehicle's, or the scenario's fixed one), without the shake nuisance.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "gesture_truth.hpp"
#include "person_figure.hpp"
#include "scenario.hpp"
#include "synthetic_params.hpp"

namespace gpilot {

struct SyntheticTruth {
  cv::Rect2f user_box, face_box;
  cv::Point2f shoulder_centre, body_centre, left_hand, right_hand;
  cv::Point2f left_elbow, right_elbow, left_wrist, right_wrist;  //!< projected joints (not in ground_truth_t)
  float hand_size = 0.0f;
  int gesture = 0;             //!< ground_truth_t::GESTURE_*
  int expected_kind = 0;       //!< hand_obs_t::KIND_*
  cv::Point2f expected_vector;
  int expected_mode = 0;       //!< gesture_cmd_t::MODE_*
  cv::Point3f expected_direction;
  cv::Point3f person_position;  //!< NED metres
  CameraPose camera;
};

struct SyntheticFrame {
  cv::Mat bgr;
  SyntheticTruth truth;
};

// Per-pixel part labels (render(..., &labels)): for tests and the contact sheet.
enum class PartLabel : uint8_t {
  Background = 0, Distractor, Legs, Torso, Head, RightArmSkin, RightHand, LeftArmSkin, LeftHand, Sleeve, Wall,
  Bystander  //!< any part of a scenario's bystander
};

class SyntheticWorld {
 public:
  // Loads the background, the face portrait and the skin colours (paths relative to the project root);
  // throws std::runtime_error naming a file that cannot be read.
  SyntheticWorld(const SyntheticParams& params, Scenario scenario, uint64_t seed);

  // Frame at scenario time t_s; camera = the vehicle's pose (closed loop) or nullopt for the scenario's
  // fixed pose. frame_index picks the sensor noise; labels (optional) receives a CV_8UC1 PartLabel image.
  SyntheticFrame render(double t_s, int64_t frame_index, const std::optional<CameraPose>& camera,
                        cv::Mat* labels = nullptr) const;

  const Scenario& scenario() const { return scenario_; }
  const SyntheticParams& params() const { return params_; }
  double focal_px() const { return focal_; }

 private:
  struct View;  // the camera of one frame
  void draw_background(cv::Mat& img, const View& v) const;
  void draw_wall(cv::Mat& img, cv::Mat* labels, const View& v) const;
  void draw_person(cv::Mat& img, cv::Mat* labels, const View& v, const FigurePose& pose, const ScenarioPerson& look) const;
  void draw_head(cv::Mat& img, cv::Mat* labels, const View& v, double step_x) const;
  bool faces_away(const View& v, double step_x) const;  //!< the person shows the camera their back
  void blend_skin(cv::Mat& img, const cv::Mat& alpha, const cv::Rect& roi) const;
  void apply_nuisances(cv::Mat& img, const ScenarioState& s, int64_t frame_index) const;

  SyntheticParams params_;
  Scenario scenario_;
  uint64_t seed_;
  FigureDims dims_;
  double focal_ = 0.0;
  cv::Mat panorama_;          // background photo, mirrored side by side so that it wraps
  double pano_period_ = 0.0;  // pixels after which the panorama repeats
  std::vector<cv::Mat> head_levels_;  // BGRA head portrait (hair darkened, elliptical alpha), a pyramid
  cv::Rect2d head_face_px_;   // the Haar face box inside head_levels_[0]
  cv::Mat skin_plane_;        // frame-sized texture of real skin colours
  cv::Mat wall_texture_;      // CV_8UC3, periodic, kWallTexel metres a pixel (empty: no wall)
  cv::Vec3d wall_centre_, wall_normal_, wall_along_;  // NED: foot of the wall behind the person, toward the camera, along it
  cv::Mat noise_bank_;        // CV_16SC3, unit Gaussian x 64, larger than a frame
  std::array<double, 4> shake_phase_{};
};

}  // namespace gpilot
