// gpilot-eval-hands --coco run as a program on the shipped data/real_people subset (and, when present, on
// ../shared/data/real_people): the counts it reports (persons read, skipped, per truth class) must match the
// annotations; and the stage's quality on real people may not fall below what it measured when it was made
// (services/hands/README.md: far from the goals, but no resting person in the shipped subset gets a hand).
// --video on a real clip of a man who makes no gesture (data/tracking/cf_tracking_sample, CC0): the drone
// would not move.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "capture/synthetic_world.hpp"
#include "config.hpp"
#include "hands/hands_params.hpp"
#include "tracker/tracker_params.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kTool = std::string(GPILOT_BIN_DIR) + "/gpilot-eval-hands";
const fs::path kShipped = fs::path(GPILOT_SOURCE_DIR) / "data" / "real_people";
const fs::path kShared = fs::path(GPILOT_SHARED_DIR) / "data" / "real_people";

// An empty folder for one test, removed afterwards.
class Scratch {
 public:
  Scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("eval_hands_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct ToolRun {
  int code;
  std::string out, err;
};

ToolRun run_tool(const std::string& args, const Scratch& dir) {
  const std::string out = dir / "stdout.txt", err = dir / "stderr.txt";
  const int status = std::system(("env -u DISPLAY " + kTool + " " + args + " > " + out + " 2> " + err).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

json run_json(const fs::path& set, const std::string& box, const Scratch& dir, const std::string& extra = "") {
  const ToolRun r = run_tool("--coco " + (set / "annotations.json").string() + " --images " + (set / "images").string() + " --box " + box +
                             " --json " + extra,
                         dir);
  EXPECT_EQ(r.code, 0) << r.err;
  try {
    return json::parse(r.out);
  } catch (const json::exception& e) {
    ADD_FAILURE() << "stdout is not one JSON object: " << e.what() << "\n" << r.out << "\n" << r.err;
    return json::object();
  }
}

void print_figures(const std::string& what, const json& j) {
  std::cout << what << ": box " << j.value("box", "?") << ", run " << j.value("persons_run", -1) << ", no face " << j.value("no_face", -1)
            << ", scored " << j.value("persons_scored", -1) << ", kind accuracy " << j.value("kind_accuracy", -1.0) << "\n"
            << "  confusion " << j["confusion"]["counts"].dump() << "\n  OUT " << j["out"].dump() << "\n  FRONT " << j["front"].dump()
            << "\n  REST " << j["rest"].dump() << "\n";
}

// Persons and arms by truth class as gesture_truth.json labels them, with the known rule differences applied
// (its "hanging beside hip" REST is AMBIGUOUS for gpilot-eval-hands, see test_truth_agreement.cpp; a person
// with two commanding arms is AMBIGUOUS, keypoint_truth.hpp).
struct Expected {
  std::map<std::string, int> persons, arms;
};

Expected expected_from_gesture_truth(const fs::path& file) {
  std::ifstream in(file);
  const json g = json::parse(in);
  Expected e;
  for (const auto& inst : g.at("instances")) {
    std::string l[2];
    int k = 0;
    for (const char* side : {"left", "right"}) {
      const auto& a = inst.at("arms").at(side);
      std::string label = a.at("label").get<std::string>();
      if (label == "REST" && a.at("reason").get<std::string>() == "hanging beside hip") label = "AMBIGUOUS";
      ++e.arms[label];
      l[k++] = label;
    }
    const auto front = [](const std::string& s) { return s.rfind("FRONT", 0) == 0; };
    const auto commands = [&](const std::string& s) { return s == "OUT" || front(s); };
    // A second rule difference: two commanding arms are none of the paper's one-armed gestures (AMBIGUOUS).
    const std::string p = (commands(l[0]) && commands(l[1]))  ? "AMBIGUOUS"
                          : (l[0] == "OUT" || l[1] == "OUT")     ? "OUT"
                          : (front(l[0]) || front(l[1]))       ? "FRONT"
                          : (l[0] == "REST" && l[1] == "REST") ? "REST"
                                                               : "AMBIGUOUS";
    ++e.persons[p];
  }
  return e;
}

void expect_counts(const json& j, int read, const Expected& e) {
  EXPECT_EQ(j.value("persons_read", -1), read);
  EXPECT_EQ(j.value("skipped_not_visible", -1), 0);
  EXPECT_EQ(j.value("image_unreadable", -1), 0);
  EXPECT_EQ(j.value("persons_usable", -1), read);
  for (const char* c : {"OUT", "FRONT", "REST", "AMBIGUOUS"}) EXPECT_EQ(j["persons_by_truth"].value(c, -1), e.persons.count(c) ? e.persons.at(c) : 0) << c;
  for (const char* c : {"OUT", "FRONT_HIGH", "FRONT_LOW", "REST", "AMBIGUOUS"})
    EXPECT_EQ(j["arms_by_truth"].value(c, -1), e.arms.count(c) ? e.arms.at(c) : 0) << c;
}

// The run's own bookkeeping: every usable person is either run or (face mode) without a face; the scored ones
// are the run ones that are not AMBIGUOUS.
void expect_consistent(const json& j) {
  const int usable = j.value("persons_usable", -1), run = j.value("persons_run", -1), no_face = j.value("no_face", -1);
  EXPECT_EQ(run + no_face, usable);
  EXPECT_EQ(j.value("persons_scored", -1) + j.value("ambiguous_not_scored", -1), run);
  int confusion = 0;
  for (const auto& row : j["confusion"]["counts"])
    for (const auto& n : row) confusion += n.get<int>();
  EXPECT_EQ(confusion, j.value("persons_scored", -1));
  // Hands that show skin are a part of their kind's persons, and the found ones a part of those.
  const json& shown = j["hand_shows_skin"];
  EXPECT_LE(shown.value("out_found", 99), shown.value("out", -1));
  EXPECT_LE(shown.value("out", 99), j["out"].value("persons", -1));
  EXPECT_LE(shown.value("out_found", 99), j["out"].value("found", -1));
  EXPECT_LE(shown.value("front_found", 99), shown.value("front", -1));
  EXPECT_LE(shown.value("front", 99), j["front"].value("persons", -1));
  if (j.value("box", "") != "annotation") {
    EXPECT_EQ(j.value("faces_found", -1), run);
  } else {
    EXPECT_EQ(no_face, 0);
  }
}

TEST(EvalHandsCli, GivenTheShippedSubsetWhenRunWithJsonThenTheCountsMatchTheAnnotations) {
  Scratch dir;
  // The subset's file: 12 images, 17 persons (COCO licences 4, 5, 7 only).
  std::ifstream in(kShipped / "annotations.json");
  const json coco = json::parse(in);
  ASSERT_EQ(coco.at("images").size(), 12u);
  ASSERT_EQ(coco.at("annotations").size(), 17u);
  for (const auto& im : coco.at("images")) {
    const int lic = im.at("license").get<int>();
    EXPECT_TRUE(lic == 4 || lic == 5 || lic == 7) << im.at("file_name") << " has licence " << lic;
  }
  // Known answers (gesture_truth.json of ../shared for these 17 persons, with the REST-beside-hip difference and
  // two commanding arms AMBIGUOUS).
  const Expected e{{{"OUT", 3}, {"FRONT", 4}, {"REST", 4}, {"AMBIGUOUS", 6}},
                   {{"OUT", 6}, {"FRONT_HIGH", 4}, {"FRONT_LOW", 5}, {"REST", 13}, {"AMBIGUOUS", 6}}};
  for (const char* box : {"annotation", "face", "keypoints"}) {
    const json j = run_json(kShipped, box, dir, std::string("--csv ") + (dir / "persons.csv") + " --png-dir " + (dir / ("png_" + std::string(box))));
    expect_counts(j, 17, e);
    expect_consistent(j);
    print_figures(std::string("shipped subset"), j);
    if (std::string(box) == "annotation") {  // measured: 0 of 4 false hands (the paper's stage: 1), 8 of 15 right
      EXPECT_EQ(j["rest"].value("false_hand", -1), 0);
      EXPECT_GE(j.value("kind_accuracy", 0.0), 0.5);
    }
    // One CSV line per person after the header; one PNG per usable person.
    const std::string csv = slurp(dir / "persons.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 18) << csv;
    EXPECT_NE(csv.find("000000000785.jpg,442619," + std::string(box)), std::string::npos);
    int pngs = 0;
    for (const auto& f : fs::directory_iterator(dir / ("png_" + std::string(box)))) pngs += f.path().extension() == ".png";
    EXPECT_EQ(pngs, 17);
  }
}

TEST(EvalHandsCli, GivenTheSharedSetWhenRunWithJsonThenTheCountsMatchItsLabels) {
  if (!fs::exists(kShared / "annotations.json") || !fs::exists(kShared / "gesture_truth.json"))
    GTEST_SKIP() << kShared << " is absent (the real_people development set is not on CI): full-set run not checked";
  Scratch dir;
  std::ifstream in(kShared / "annotations.json");
  const int read = static_cast<int>(json::parse(in).at("annotations").size());
  const Expected e = expected_from_gesture_truth(kShared / "gesture_truth.json");
  for (const char* box : {"annotation", "face", "keypoints"}) {
    const json j = run_json(kShared, box, dir);
    expect_counts(j, read, e);
    expect_consistent(j);
    print_figures(std::string("../shared real_people"), j);
    if (std::string(box) == "keypoints") {  // 60 of 62 persons have the nose/eyes/ears a face box needs
      EXPECT_EQ(j.value("persons_run", -1), 60);
    }
    if (std::string(box) == "annotation") {  // measured: 6 of 20 false hands (the paper's stage: 13), 44 % right
      EXPECT_LE(j["rest"].value("false_hand", 99), 7);
      EXPECT_GE(j.value("kind_accuracy", 0.0), 0.40);
    }
  }
}

TEST(EvalHandsCli, GivenHelpWhenAskedThenTheTruthRulesArePrinted) {
  Scratch dir;
  const ToolRun r = run_tool("--help", dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("1. OUT:   s >= 0.85 and (angle from down >= 45 deg or W above the shoulder line)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--box"), std::string::npos);
}

TEST(EvalHandsCli, GivenABrokenAnnotationFileWhenRunThenAnErrorNamingItAndNoCrash) {
  Scratch dir;
  {
    std::ofstream(dir / "bad.json") << R"({"images": [], "annotations": [], "categories": [{"id": 1}]})";
  }
  const ToolRun r = run_tool("--coco " + (dir / "bad.json") + " --images " + kShipped.string(), dir);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("not a person-keypoints file"), std::string::npos) << r.err;
}

TEST(EvalHandsCli, GivenAFolderWithoutTheImagesWhenRunThenAnErrorNotZeros) {
  Scratch dir;
  fs::create_directories(dir / "empty");
  const ToolRun r = run_tool("--coco " + (kShipped / "annotations.json").string() + " --images " + (dir / "empty") + " --json", dir);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.err.find("none of the 12 images with persons"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(EvalHandsCli, GivenCocoWithoutImagesWhenRunThenAUsageError) {
  Scratch dir;
  const ToolRun r = run_tool("--coco " + (kShipped / "annotations.json").string(), dir);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--images"), std::string::npos) << r.err;
}

TEST(EvalHandsCli, GivenTheSyntheticModeWhenRunThenItStillScoresAScenario) {
  Scratch dir;
  const ToolRun r = run_tool("--scenario tour --stride 50 --png-dir '' --json", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j.value("scenario", ""), "tour");
  EXPECT_EQ(j.value("frames", -1), 30);  // 1500 frames, every 50th
  std::cout << "synthetic tour (stride 50): kind accuracy " << j.value("kind_accuracy", -1.0) << "\n";
}

// The man in data/tracking/cf_tracking_sample (CC0, 53 frames, 640 x 360) stands with his hands at rest in an
// orange T-shirt the skin table calls skin, pink hydrangeas beside him. The user box: the body box the tracker
// would make for his ~14 px face (2.75 x 7 face sizes) on his first-frame position (init_rect.txt is his upper
// body). The paper's stage took the shirt for a hand on every frame and decided FINE on 43 (84.9 %); before the
// clothing and torso-size rules ours decided CLOSER on 17 (32.1 %); now none.
const std::string kRestingClip = std::string(GPILOT_SOURCE_DIR) + "/data/tracking/cf_tracking_sample/img";

TEST(EvalHandsCli, GivenARealClipOfAManAtRestWhenRunThenNoCommandWouldMoveTheDrone) {
  Scratch dir;
  const ToolRun r = run_tool("--video " + kRestingClip + " --gesture none --init-box 261,50,39,132 --json --csv " + (dir / "f.csv") +
                                 " --mp4 " + (dir / "f.mp4"),
                             dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  std::cout << "cf_tracking_sample at rest: " << r.out << "\n";
  EXPECT_EQ(j.value("frames", -1), 53);
  EXPECT_EQ(j.value("frames_tracking", -1), 53);
  EXPECT_EQ(j.value("frames_decided", -1), 53);
  EXPECT_LE(j.value("rest_moving_command_share", 1.0), 0.20);  // the hands issue's bar for frames without a gesture
  EXPECT_EQ(j.value("rest_frames_judged", -1), 33);            // from 0.8 s (20 frames) on
  EXPECT_EQ(j.value("moving_command_frames", -1), 0);          // measured: none on any frame
  std::ifstream csv(dir / "f.csv");
  EXPECT_EQ(std::count(std::istreambuf_iterator<char>(csv), std::istreambuf_iterator<char>(), '\n'), 54);
  EXPECT_GT(fs::file_size(dir / "f.mp4"), 10000u);
  // The clip does defeat the paper's stage: it flies FINE on the shirt.
  const ToolRun paper = run_tool("--video " + kRestingClip + " --init-box 261,50,39,132 --json --set hands.method=skin --set hands.skin.adapt.enabled=false "
                                 "--set hands.max_blob_hand_areas=0 --set hands.reach_ratio=0 --set hands.out_min_angle_deg=0 "
                                 "--set hands.arm_connected=false --set hands.front_max_upright=0 --set hands.front_max_hand_areas=0",
                                 dir);
  ASSERT_EQ(paper.code, 0) << paper.err;
  EXPECT_GE(json::parse(paper.out).value("rest_moving_command_share", 0.0), 0.5);
}

TEST(EvalHandsCli, GivenABadVideoInputWhenRunThenAClearErrorAndNoCrash) {
  Scratch dir;
  ToolRun r = run_tool("--video " + kRestingClip + " --init-box 261,50,-39,132", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("want x,y,w,h"), std::string::npos) << r.err;
  r = run_tool("--video " + (dir / "missing.mp4"), dir);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("missing.mp4"), std::string::npos) << r.err;
  fs::create_directories(dir / "empty");
  r = run_tool("--video " + (dir / "empty"), dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("empty"), std::string::npos) << r.err;
  r = run_tool("--video " + kRestingClip + " --coco x.json", dir);
  EXPECT_NE(r.code, 0);
}

// A clip with gestures and their truth, as someone would bring one: the first 12 s of the synthetic tour (rest,
// the right arm out, the left arm out) written as JPEG files, the truth as frame ranges from the world's own.
// The tool, starting from the face search, must find the user and judge it as the e2e tests do.
TEST(EvalHandsCli, GivenAClipWithAGestureTruthWhenRunThenEachGestureIsJudgedFromItsSettlingOn) {
  Scratch dir;
  fs::create_directories(dir / "img");
  const gpilot::Config config;
  const gpilot::SyntheticWorld world(config.section<gpilot::SyntheticParams>("synthetic"), gpilot::Scenario::load("tour"), 1);
  std::ofstream truth(dir / "truth.csv");
  truth << "# first,last,GESTURE\n";
  int first = 0, gesture = -1;
  const int frames = 300;
  for (int i = 0; i <= frames; ++i) {
    const int g = i < frames ? world.render(i / 25.0, i, std::nullopt).truth.gesture : -2;
    if (i < frames) {
      char name[32];
      std::snprintf(name, sizeof name, "%05d.jpg", i);
      cv::imwrite(dir / ("img/" + std::string(name)), world.render(i / 25.0, i, std::nullopt).bgr, {cv::IMWRITE_JPEG_QUALITY, 95});
    }
    if (g != gesture) {
      if (gesture >= 0) truth << first << ',' << i - 1 << ',' << gpilot::gesture_name(gesture) << '\n';
      first = i, gesture = g;
    }
  }
  truth.close();
  std::cout << slurp(dir / "truth.csv");
  const ToolRun r = run_tool("--video " + (dir / "img") + " --truth " + (dir / "truth.csv") + " --json", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  std::cout << r.out << "\n";
  EXPECT_EQ(j.value("frames", -1), frames);
  EXPECT_GE(j.value("tracks_started", 0), 1);
  EXPECT_GT(j.value("gesture_frames_judged", 0), 150);
  EXPECT_GE(j.value("gesture_hand_right_share", 0.0), 0.8);
  EXPECT_GE(j["by_gesture"]["OUT"].value("command_right", 0), j["by_gesture"]["OUT"].value("judged", -1) * 8 / 10);
  EXPECT_LE(j.value("rest_moving_command_share", 1.0), 0.2);
  // A malformed truth line is an error naming it, not a score
  std::ofstream(dir / "bad.csv") << "0,10,REST\n20,5,OUT\n";
  const ToolRun bad = run_tool("--video " + (dir / "img") + " --truth " + (dir / "bad.csv"), dir);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("line 2"), std::string::npos) << bad.err;
}

}  // namespace
