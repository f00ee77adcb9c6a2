// The keypoint truth rules against ../shared/data/real_people/gesture_truth.json (labels made by the data set's
// author with the README's rules). The two rule sets differ on purpose in one place: the README's rule 4 also
// calls REST a bent arm "hanging beside the hip" (wrist outside the torso span, below the torso centre, arm
// <= 45 deg from down); ours (the issue's) only a wrist below the hip line, so such arms are AMBIGUOUS here.
// OUT, FRONT_HIGH and FRONT_LOW must agree exactly; REST/AMBIGUOUS differences are printed and must be of
// that one kind.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "coco_keypoints.hpp"
#include "keypoint_truth.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

const fs::path kShared = fs::path(GPILOT_SHARED_DIR) / "data" / "real_people";

bool front_or_out(const std::string& label) { return label == "OUT" || label == "FRONT_HIGH" || label == "FRONT_LOW"; }

TEST(KeypointTruthAgreement, GivenTheSharedSetWhenEveryArmIsClassifiedThenOutAndFrontAgreeWithItsLabels) {
  if (!fs::exists(kShared / "gesture_truth.json") || !fs::exists(kShared / "annotations.json"))
    GTEST_SKIP() << kShared << " is absent (the real_people development set is not on CI): agreement not checked";
  const CocoKeypointFile coco = CocoKeypointFile::load((kShared / "annotations.json").string());
  std::map<int64_t, const CocoAnnotation*> by_id;
  for (const auto& a : coco.annotations()) by_id[a.id] = &a;
  std::ifstream in(kShared / "gesture_truth.json");
  const nlohmann::json labels = nlohmann::json::parse(in);

  int arms = 0, agree = 0, beside_hip = 0;
  std::map<std::string, int> theirs_count, ours_count;
  for (const auto& inst : labels.at("instances")) {
    const int64_t id = inst.at("annotation_id").get<int64_t>();
    ASSERT_TRUE(by_id.count(id)) << "annotation " << id << " of gesture_truth.json is not in annotations.json";
    const CocoAnnotation& a = *by_id[id];
    const PersonKeypointTruth t = keypoint_truth(BodyKeypoints::from([&](const std::string& name) -> std::optional<BodyPoint> {
      const auto k = coco.keypoint(a, name);
      if (!k) return std::nullopt;
      return BodyPoint{k->p, k->v};
    }));
    ASSERT_TRUE(t.usable) << id << ": " << t.skip_reason;
    // The face box is the README's.
    if (inst.at("face_box").is_null()) {
      EXPECT_FALSE(t.face_box.has_value()) << id;
    } else {
      ASSERT_TRUE(t.face_box.has_value()) << id;
      const auto& f = inst.at("face_box");
      EXPECT_NEAR(t.face_box->x, f[0].get<double>(), 0.051) << id;
      EXPECT_NEAR(t.face_box->y, f[1].get<double>(), 0.051) << id;
      EXPECT_NEAR(t.face_box->width, f[2].get<double>(), 0.051) << id;
      EXPECT_NEAR(t.face_box->height, f[3].get<double>(), 0.051) << id;
    }
    EXPECT_NEAR(t.torso_height, inst.at("torso_height").get<double>(), 0.051) << id;
    for (const auto& [side, ours] : {std::pair<const char*, const ArmKeypointTruth*>{"left", &t.left}, {"right", &t.right}}) {
      const auto& arm = inst.at("arms").at(side);
      const std::string theirs = arm.at("label").get<std::string>();
      const std::string mine = arm_truth_name(ours->label);
      ++arms;
      ++theirs_count[theirs];
      ++ours_count[mine];
      const std::string where = inst.at("file_name").get<std::string>() + " #" + std::to_string(id) + " " + side;
      // The measurements the labels come from.
      EXPECT_NEAR(ours->straightness, arm.at("straightness").get<double>(), 0.0006) << where;
      EXPECT_NEAR(ours->angle_from_down_deg, arm.at("angle_from_down_deg").get<double>(), 0.051) << where;
      EXPECT_EQ(ours->wrist_above_shoulder_line, arm.at("wrist_above_shoulder_line").get<bool>()) << where;
      // The shared set's "wrist_in_torso_span" is the FRONT region: within the span AND between the lines.
      const bool in_torso = ours->wrist_in_torso_span && !ours->wrist_above_shoulder_line && !ours->wrist_below_hip_line;
      EXPECT_EQ(in_torso, arm.at("wrist_in_torso_span").get<bool>()) << where;
      EXPECT_EQ(ours->wrist_at_face, arm.at("wrist_at_face").get<bool>()) << where;
      if (theirs == mine) {
        ++agree;
        continue;
      }
      std::cout << "differs: " << where << ": gesture_truth " << theirs << " (" << arm.at("reason").get<std::string>()
                << "), ours " << mine << " (" << ours->reason << ")\n";
      EXPECT_FALSE(front_or_out(theirs) || front_or_out(mine)) << where << ": OUT/FRONT must agree";
      // The one known difference: the README's "hanging beside hip" REST.
      const bool known = theirs == "REST" && mine == "AMBIGUOUS" && arm.at("reason").get<std::string>() == "hanging beside hip";
      EXPECT_TRUE(known) << where;
      beside_hip += known;
    }
  }
  std::cout << arms << " arms, " << agree << " labels agree, " << beside_hip
            << " differ only by the README's 'hanging beside hip' REST (AMBIGUOUS here)\n";
  for (const auto& [label, n] : theirs_count) std::cout << "  " << label << ": gesture_truth " << n << ", ours " << ours_count[label] << "\n";
  EXPECT_EQ(arms, 124);
  EXPECT_EQ(theirs_count["OUT"], ours_count["OUT"]);
  EXPECT_EQ(theirs_count["FRONT_HIGH"], ours_count["FRONT_HIGH"]);
  EXPECT_EQ(theirs_count["FRONT_LOW"], ours_count["FRONT_LOW"]);
  EXPECT_EQ(arms - agree, beside_hip);
}

}  // namespace
}  // namespace gpilot
