// Scenario files: the shipped scenarios load, the script blends smoothly from pose to pose, keys carry over,
// and a bad file is an error that names the file and the key.
#include <gtest/gtest.h>

#include <cmath>

#include "gpilot/ground_truth_t.hpp"
#include "person_figure.hpp"
#include "scenario.hpp"

namespace gpilot {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    Scenario::parse(yaml, "test.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(Scenario, BareNameLoadsTheShippedTour) {
  const Scenario s = Scenario::load("tour");
  EXPECT_EQ(s.name(), "tour");
  EXPECT_DOUBLE_EQ(s.duration_s(), 60.0);
  EXPECT_NE(s.origin().find("deploy/scenarios/tour.yaml"), std::string::npos);
  EXPECT_GE(s.keyframes().size(), 10u);
  // The tour shows every gesture.
  for (int g = ground_truth_t::GESTURE_REST; g <= ground_truth_t::GESTURE_FURTHER; ++g) {
    bool seen = false;
    for (const auto& k : s.keyframes()) seen = seen || k.state.gesture == g;
    EXPECT_TRUE(seen) << gesture_name(g);
  }
}

TEST(Scenario, EveryShippedScenarioLoads) {
  for (const char* name : {"tour", "fine-piloting", "closer-further", "idle", "nuisances", "warm-wall", "dark-skin",
                           "bystander", "far", "far-no-face", "talking", "orange-shirt", "walk-out", "turn-around"}) {
    SCOPED_TRACE(name);
    const Scenario s = Scenario::load(name);
    EXPECT_GT(s.duration_s(), 10.0);
  }
}

TEST(Scenario, MissingFileIsAClearError) {
  try {
    Scenario::load("no-such-scenario");
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-scenario"), std::string::npos) << e.what();
  }
}

TEST(Scenario, BlendsSmoothlyAndHoldsEachPose) {
  // GIVEN rest at t=0, then the right arm out at t=2 with a 1 s transition
  const Scenario s = Scenario::parse(
      "keyframes:\n"
      "  - {t: 0, gesture: REST, right_arm: rest}\n"
      "  - {t: 2, gesture: OUT, right_arm: out, transition_s: 1.0, light: 0.5, turn_deg: 180}\n",
      "x.yaml");
  // THEN before the move the pose is rest, half-way it is half-way (smoothstep(0.5) = 0.5), after it is out
  EXPECT_DOUBLE_EQ(s.state_at(1.9).right_arm.angle_deg, 0.0);
  EXPECT_NEAR(s.state_at(2.5).right_arm.angle_deg, 45.0, 1e-9);
  EXPECT_NEAR(s.state_at(2.5).light, 0.75, 1e-9);
  EXPECT_NEAR(s.state_at(2.5).turn_deg, 90.0, 1e-9);  // turning round, side-on half-way
  EXPECT_DOUBLE_EQ(s.state_at(3.0).right_arm.angle_deg, 90.0);
  EXPECT_DOUBLE_EQ(s.state_at(100.0).right_arm.angle_deg, 90.0);
  // the gesture label switches half-way through the transition
  EXPECT_EQ(s.state_at(2.4).gesture, ground_truth_t::GESTURE_REST);
  EXPECT_EQ(s.state_at(2.6).gesture, ground_truth_t::GESTURE_OUT);
  // the left arm, never given, stays at rest; default duration = last keyframe + transition + 2 s
  EXPECT_DOUBLE_EQ(s.state_at(3.0).left_arm.angle_deg, ArmPose::preset("rest").angle_deg);
  EXPECT_DOUBLE_EQ(s.duration_s(), 5.0);
}

TEST(Scenario, AnInterruptedMoveStartsFromWhereItGot) {
  const Scenario s = Scenario::parse(
      "keyframes:\n"
      "  - {t: 0, right_arm: {angle_deg: 0}}\n"
      "  - {t: 1, right_arm: {angle_deg: 100}, transition_s: 2}\n"
      "  - {t: 2, right_arm: {angle_deg: 0}, transition_s: 1}\n",
      "x.yaml");
  // at t=2 the first move is half done (50 deg); the second starts there: no jump
  EXPECT_NEAR(s.state_at(2.0).right_arm.angle_deg, 50.0, 1e-9);
  EXPECT_NEAR(s.state_at(2.5).right_arm.angle_deg, 25.0, 1e-9);
  EXPECT_NEAR(s.state_at(3.0).right_arm.angle_deg, 0.0, 1e-9);
}

TEST(Scenario, HandOffsetPlacesTheHand) {
  // GIVEN a hand 0.3 m in front of the shoulder and 0.2 m below it
  const ArmPose p = ArmPose::from_hand_offset(0.0, -0.2, 0.3);
  const cv::Point3d h = hand_offset_of(FigureDims{}, p);
  EXPECT_NEAR(h.x, 0.0, 1e-9);
  EXPECT_NEAR(h.y, -0.2, 1e-9);
  EXPECT_NEAR(h.z, 0.3, 1e-9);
}

TEST(Scenario, PersonFacesTheCameraByDefault) {
  const Scenario s = Scenario::parse("camera: {north: 1, east: 2, down: -1.5, yaw_deg: 90}\nkeyframes: [{t: 0}]\n", "x");
  // 3 m along the camera's yaw (east), facing back west
  EXPECT_NEAR(s.person().north, 1.0, 1e-9);
  EXPECT_NEAR(s.person().east, 5.0, 1e-9);
  EXPECT_NEAR(std::fabs(s.person().facing_yaw), M_PI / 2, 1e-9);
  EXPECT_LT(s.person().facing_yaw, 0.0);
}

TEST(Scenario, BadFilesNameTheKey) {
  EXPECT_NE(error_of("keyframes: []").find("keyframes"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 0, gesture: WAVE}]").find("keyframes[0].gesture"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 0, right_arm: flap}]").find("flap"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 1}, {t: 1}]").find("keyframes[1].t"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 0, lihgt: 2}]").find("keyframes[0].lihgt: unknown key"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 0, light: -1}]").find("keyframes[0].light"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 0, turn_deg: 400}]").find("keyframes[0].turn_deg"), std::string::npos);
  EXPECT_NE(error_of("camera: {north: x}\nkeyframes: [{t: 0}]").find("camera.north: not a number"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 0}").find("test.yaml: not valid YAML"), std::string::npos);
  EXPECT_NE(error_of("keyframes: [{t: 0, right_arm: {hand: [1, 2]}}]").find("right_arm.hand"), std::string::npos);
}


// Bystanders (issue 13): GIVEN a walker who crosses from east -2 to +2 over 4 s and a waver whose right arm
// swings ±20° about 140° at 1 Hz WHEN the script is read THEN they are where and as the keyframes say, between
// them smoothly; their clothes and names are the file's.
TEST(Scenario, BystandersWalkAndWaveByTheirOwnKeyframes) {
  const Scenario s = Scenario::parse(R"(
bystanders:
  - name: walker
    shirt_bgr: [10, 20, 30]
    keyframes:
      - {t: 0, north: 1.5, east: -2}
      - {t: 10, east: 2, transition_s: 4}
  - keyframes:
      - {t: 0, north: 3, east: 1}
      - {t: 5, right_arm: {preset: up, angle_deg: 140}, wave_deg: 20, wave_hz: 1, transition_s: 0}
keyframes:
  - {t: 0, gesture: REST}
)", "test.yaml");
  ASSERT_EQ(s.bystanders().size(), 2u);
  const Bystander& walker = s.bystanders()[0];
  EXPECT_EQ(walker.name, "walker");
  EXPECT_EQ(walker.look.shirt_bgr, (std::array<int, 3>{10, 20, 30}));
  EXPECT_EQ(s.bystanders()[1].name, "bystander 2");
  EXPECT_DOUBLE_EQ(walker.state_at(5).east, -2.0);
  EXPECT_DOUBLE_EQ(walker.state_at(5).north, 1.5);
  EXPECT_DOUBLE_EQ(walker.state_at(12).east, 0.0);  // half-way: smoothstep(0.5) = 0.5
  EXPECT_DOUBLE_EQ(walker.state_at(20).east, 2.0);
  const Bystander& waver = s.bystanders()[1];
  EXPECT_DOUBLE_EQ(waver.state_at(4).right_arm.angle_deg, 0.0);          // at rest before
  EXPECT_NEAR(waver.state_at(6.0).right_arm.angle_deg, 140.0, 1e-9);     // sin(2 pi 1 Hz 6 s) = 0
  EXPECT_NEAR(waver.state_at(6.25).right_arm.angle_deg, 160.0, 1e-9);    // a quarter period: +20
  EXPECT_NEAR(waver.state_at(6.75).right_arm.angle_deg, 120.0, 1e-9);
}

TEST(Scenario, BadBystandersNameTheKey) {
  EXPECT_NE(error_of("bystanders: {a: 1}\nkeyframes: [{t: 0}]").find("bystanders: a list"), std::string::npos);
  EXPECT_NE(error_of("bystanders: [{keyframes: [{t: 0, north: 1}]}]\nkeyframes: [{t: 0}]")
                .find("bystanders[0].keyframes[0]: the first keyframe says where they stand"),
            std::string::npos);
  EXPECT_NE(error_of("bystanders: [{hat: red, keyframes: [{t: 0, north: 1, east: 0}]}]\nkeyframes: [{t: 0}]")
                .find("bystanders[0].hat: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("bystanders: [{keyframes: [{t: 0, north: 1, east: 0, wave_deg: 100}]}]\nkeyframes: [{t: 0}]")
                .find("bystanders[0].keyframes[0].wave_deg: value 100 outside [0, 90]"),
            std::string::npos);
}

}  // namespace
}  // namespace gpilot
