// A scenario of the synthetic world: a YAML file with the scene (background, where the person stands, the
// camera's fixed pose) and a timed script of keyframes (arm poses, the intended gesture, nuisances) that the
// person moves through with smooth transitions. Pure data: no clock, no rendering.
//
// File format (deploy/scenarios/*.yaml; every key but `keyframes` is optional):
//   name: tour
//   description: every gesture of the paper in turn
//   duration_s: 60                     # default: last keyframe + its transition + 2 s
//   background: data/backgrounds/building.jpg
//   background_grade: {saturation: 0.4, red_gain: 0.85, blue_gain: 1.15, blur_sigma: 1.5}   # the defaults
//   transition_s: 1.0                  # default length of the move into each keyframe
//   camera: {north: 0, east: 0, down: -1.5, yaw_deg: 0}        # fixed pose when no VEHICLE_STATE
//   person: {north: 3, east: 0, facing_yaw_deg: 180, skin_tone: light,
//            shirt_bgr: [150, 80, 40], trousers_bgr: [60, 50, 45]}  # facing: default, turns to face the camera
//   person: {..., sleeves: short, tint_face: false}  # short (default): bare forearms and the end of the upper
//            # arm; long: shirt down to the wrists, only the hands bare. tint_face: the pasted portrait's face
//            # recoloured toward the skin tone (per-channel gains, mean face colour -> mean tone colour), so that
//            # face and hands match; false (default) pastes it as shot (a light face whatever the tone).
//   distractor: {left: 1.3, up: 1.5, behind: 2.0, radius: 0.12}   # skin-coloured ball, person frame, m
//   wall: {distance_m: 1.0, bgr: [130, 170, 215], texture: wood, width_m: 0, height_m: 0, shading: 0.25}
//            # a wall (vertical plane) distance_m behind the person, facing the scenario's camera, in front of
//            # the background photo: fixed in the world (the closed-loop camera sees it with parallax; the
//            # person's side steps do not move it). bgr: its mean colour; texture: plaster (mottled, fine
//            # grain), wood (vertical boards 12.5 cm wide, per-board tone, grain, dark joints) or flat; width_m /
//            # height_m: 0 = unbounded (it fills the view), else a rectangle centred behind the person, from the
//            # ground up; shading: how much darker the wall gets away from its light (a lamp up and to the
//            # person's right, 0 = evenly lit). The texture is procedural, the same for every seed.
//   bystanders:                        # other people in the scene (issue 13: the user, not a bystander)
//     - name: walker                   # for messages and tools
//       shirt_bgr: [40, 40, 150]       # also trousers_bgr, sleeves (as person's); the same face portrait and
//                                      # skin tone as the user, always facing the camera (a passer-by
//                                      # glancing at the drone: a frontal face, the harder case for a tracker)
//       keyframes:                     # as the user's, with their own keys: north, east (NED metres, where
//         - {t: 0, north: 1.6, east: -3}   # they stand; smooth moves between keyframes, so a walk is a
//         - {t: 8, east: 3, transition_s: 5}   # keyframe with a long transition), right_arm, left_arm,
//         - {t: 20, right_arm: up, wave_deg: 25, wave_hz: 1.5}   # wave_deg: the right arm's angle
//                                      # swings ± this at wave_hz (a wave); 0 = still
//     A bystander has no ground truth of their own in GROUND_TRUTH (its boxes are the user's); what they do
//     must never reach a command: the user's expected mode is all the truth there is.
//   keyframes:
//     - {t: 0, gesture: REST, right_arm: rest, left_arm: rest}
//     - {t: 4, gesture: OUT, right_arm: out, transition_s: 1.5}
//     - {t: 8, right_arm: {preset: out, angle_deg: 120}}
//     - {t: 12, gesture: CLOSER, right_arm: {hand: [-0.14, -0.14, 0.30]}}
// A keyframe starts moving at `t` from the state reached so far and arrives after its transition (smoothstep);
// a key it does not give keeps its previous value. Keys: gesture (REST OUT UP DOWN CLOSER FURTHER),
// right_arm / left_arm (a preset name: rest out up down front_high front_low; or a map with `preset`,
// `angle_deg`, `extension`, `forward_deg`; or {hand: [out, up, forward]} metres from the shoulder),
// step_m (sideways step to the person's left, m), turn_deg (the person turned from where they face, degrees,
// positive to their left: 180 shows the camera their back), light (brightness gain), shake_deg (camera shake
// amplitude), noise_sigma (sensor noise, grey levels), blur_px (horizontal motion blur length),
// jpeg_quality (0 = off), distractor (true/false). Numbers blend smoothly; gesture, jpeg_quality and
// distractor switch half-way through the transition.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace gpilot {

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// NED metres, yaw rad (0 = north, positive clockwise seen from above), the camera's optical axis level.
struct CameraPose {
  double north = 0.0, east = 0.0, down = 0.0, yaw = 0.0;
};

// One arm. The hand sits at extension × arm length from the shoulder, in the direction given by angle_deg in
// the body's frontal plane (0 = straight down, 90 = straight out sideways, 180 = straight up; negative =
// across the body) tilted forward (toward where the person faces) by forward_deg. The elbow bends to fit.
struct ArmPose {
  double angle_deg = 0.0;
  double extension = 1.0;   //!< 0.3 .. 1 of the full arm length (shoulder to hand centre)
  double forward_deg = 6.0;

  static ArmPose preset(const std::string& name);  // throws ScenarioError for an unknown name
  // The pose that puts the hand centre at (out, up, forward) metres from the shoulder.
  static ArmPose from_hand_offset(double out, double up, double forward);
};

// Everything that changes along the script, at one instant.
struct ScenarioState {
  ArmPose right_arm, left_arm;  //!< the person's own right and left
  int gesture = 0;              //!< ground_truth_t::GESTURE_*
  double step_m = 0.0;          //!< sideways offset of the person, to their left, metres
  double turn_deg = 0.0;        //!< the person turned from where they face, degrees, positive to their left
  double light = 1.0;           //!< brightness gain applied to the whole frame
  double shake_deg = 0.0;       //!< camera shake amplitude (yaw and pitch), degrees
  double noise_sigma = 0.0;     //!< Gaussian sensor noise, grey levels
  double blur_px = 0.0;         //!< horizontal motion blur, pixels
  int jpeg_quality = 0;         //!< JPEG round trip at this quality; 0 = none
  bool distractor = false;      //!< the skin-coloured ball in the background is visible
};

struct ScenarioPerson {
  double north = 3.0, east = 0.0;  //!< the point between the feet, on the ground (down = 0), NED metres
  double facing_yaw = 0.0;         //!< rad, the direction the person faces (toward the scenario's camera by default)
  bool faces_camera = true;        //!< turns to keep facing the camera as it moves (false when facing_yaw_deg is given)
  std::string skin_tone = "light";
  std::array<int, 3> shirt_bgr{{150, 82, 40}};
  std::array<int, 3> trousers_bgr{{70, 55, 45}};
  bool long_sleeves = false;       //!< sleeves: long (only the hands bare) or short (the default: bare forearms)
  bool tint_face = false;          //!< recolour the pasted face toward the skin tone
};

// A wall behind the person (see the format comment above); absent unless the scenario has `wall`.
struct ScenarioWall {
  bool present = false;
  double distance_m = 1.0;                   //!< behind the person's feet, along the scenario camera's line to them
  std::array<int, 3> bgr{{130, 170, 215}};   //!< mean colour
  std::string texture = "plaster";           //!< plaster | wood | flat
  double width_m = 0.0, height_m = 0.0;      //!< 0 = unbounded
  double shading = 0.25;                     //!< darkening away from the light, 0..0.8
};

struct ScenarioDistractor {
  double left = 1.3, up = 1.5, behind = 2.0, radius = 0.12;  //!< person frame, metres
};

// Colour grading of the background photograph: saturation (1 = as shot, 0 = grey) then per-channel gains. The
// default, a muted and cool look (overcast light), keeps the photographs' warm beige walls from reading as
// skin to a histogram skin model trained on UCI pixels (with the photos as shot, 2-8 % of building.jpg and
// 28 % of home.jpg are "skin"); {1, 1, 1} shows them as shot, a nuisance of its own. blur_sigma (pixels of
// the frame at the reference pose) puts the far backdrop a little out of focus, so that its strong window
// grid does not outweigh the person in a tracker's features (0 = sharp).
struct BackgroundGrade {
  double saturation = 0.4, red_gain = 0.85, blue_gain = 1.15, blur_sigma = 1.5;
};

struct Keyframe {
  double t_s = 0.0;
  double transition_s = 1.0;
  ScenarioState state;  //!< the full state once the transition is over
};

// Another person in the scene (see the format comment above): where they stand and how their arms move.
struct BystanderState {
  double north = 0.0, east = 0.0;  //!< NED metres, the point between the feet
  ArmPose right_arm, left_arm;
  double wave_deg = 0.0;           //!< the right arm's angle swings ± this ...
  double wave_hz = 1.5;            //!< ... at this frequency
};

struct BystanderKeyframe {
  double t_s = 0.0;
  double transition_s = 1.0;
  BystanderState state;
};

struct Bystander {
  std::string name;
  ScenarioPerson look;  //!< shirt, trousers, sleeves (the place is in the keyframes; always faces the camera)
  std::vector<BystanderKeyframe> keyframes;
  std::vector<BystanderState> starts;  //!< the state each keyframe's move starts from

  // The state at scenario time t_s, the wave applied (its right arm's angle at that instant).
  BystanderState state_at(double t_s) const;
};

class Scenario {
 public:
  // A bare name ("tour") means deploy/scenarios/<name>.yaml under the project root; anything else is a path.
  static Scenario load(const std::string& path_or_name);
  static Scenario parse(const std::string& yaml, const std::string& origin);

  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  const std::string& origin() const { return origin_; }
  double duration_s() const { return duration_s_; }
  const std::string& background() const { return background_; }
  const BackgroundGrade& background_grade() const { return grade_; }
  const CameraPose& camera() const { return camera_; }
  const ScenarioPerson& person() const { return person_; }
  const ScenarioDistractor& distractor() const { return distractor_; }
  const ScenarioWall& wall() const { return wall_; }
  const std::vector<Bystander>& bystanders() const { return bystanders_; }
  const std::vector<Keyframe>& keyframes() const { return keyframes_; }

  // The state at scenario time t_s (clamped to the script).
  ScenarioState state_at(double t_s) const;

  // One instant per keyframe at which its pose is fully reached and held: the script's key poses.
  std::vector<double> key_times() const;
  // The first of those whose keyframe holds this gesture (ground_truth_t::GESTURE_*); nullopt if none does.
  std::optional<double> key_time_of(int gesture) const;

 private:
  std::string name_, description_, origin_;
  double duration_s_ = 0.0;
  std::string background_ = "data/backgrounds/building.jpg";
  BackgroundGrade grade_;
  CameraPose camera_{0.0, 0.0, -1.5, 0.0};
  ScenarioPerson person_;
  ScenarioDistractor distractor_;
  ScenarioWall wall_;
  std::vector<Bystander> bystanders_;
  std::vector<Keyframe> keyframes_;
  std::vector<ScenarioState> starts_;  // the state each keyframe's move starts from
};

// "REST" -> ground_truth_t::GESTURE_REST ...; -1 if unknown. And back.
int gesture_from_name(const std::string& name);
const char* gesture_name(int gesture);

}  // namespace gpilot
