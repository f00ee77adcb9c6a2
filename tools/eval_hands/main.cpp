// gpilot-eval-hands: the hands stage measured apart from the tracker, on
//   --scenario: a synthetic scenario against the synthetic world's ground truth (synthetic_eval.hpp), or
//   --coco:     real photos with COCO person keypoints against truth from the keypoints (coco_eval.hpp),
//   --video:    a real clip through tracker, hands and decide, a person who makes no gesture (video_eval.hpp).
// A thin CLI: the work is in the files next to it.
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "coco_eval.hpp"
#include "hands/hands_params.hpp"
#include "keypoint_truth.hpp"
#include "service_cli.hpp"
#include "synthetic_eval.hpp"
#include "system/opencv_threads.hpp"
#include "tracker/tracker_params.hpp"
#include "video_eval.hpp"

using namespace gpilot;

namespace {

// --method M is --set hands.method=M, so the config's rules (a method this build has) judge it.
std::vector<std::string> method_as_set(int argc, char** argv) {
  std::vector<std::string> args(argv, argv + argc);
  for (size_t i = 1; i < args.size(); ++i) {
    if (args[i] == "--method" && i + 1 < args.size()) {
      args[i] = "--set";
      args[i + 1] = "hands.method=" + args[i + 1];
    } else if (args[i].rfind("--method=", 0) == 0) {
      args[i] = "--set=hands.method=" + args[i].substr(9);
    }
  }
  return args;
}

}  // namespace

int main(int argc_given, char** argv_given) {
  std::vector<std::string> args = method_as_set(argc_given, argv_given);
  std::vector<char*> argv_vec;
  for (auto& a : args) argv_vec.push_back(a.data());
  const int argc = static_cast<int>(argv_vec.size());
  char** argv = argv_vec.data();
  ServiceCli cli("gpilot-eval-hands",
                 "Scores the hands stage (hands.method, built as the service builds it) apart from the tracker.\n"
                 "--scenario NAME (default): a synthetic scenario against its ground truth, with the TRUE user box and the true face on the\n  frames the tracker would hand it over (the first, then every tracker.face_recheck_frames):\n"
                 "  kind accuracy and confusion matrix, OUT angle and length error, FRONT higher/lower success, ms per frame;\n"
                 "  a few annotated PNGs (skin in red, hand square, vector).\n"
                 "--coco ANNOTATIONS.json --images DIR: every annotated person of real photos (COCO person keypoints),\n"
                 "  one fresh start of the method per person, with\n"
                 "  --box annotation: the largest Haar face in the tracker's face re-check window of the annotation's bbox,\n"
                 "                    and the body box the tracker makes from it (body_from_face, section tracker); no\n"
                 "                    face there: the annotation's bbox itself;\n"
                 "  --box face: the body box the tracker would make (body_from_face, section tracker) from the Haar face\n"
                 "              found in the person's head region (nose/eyes/ears); no face: counted, not scored.\n"
                 "  --box keypoints: the same from the face box the nose/eyes/ears keypoints span (the hands stage apart\n"
                 "              from face finding: a tracker that never misses a face).\n"
                 "  The face goes to the stage too (its skin, the neck below it); the stage works on the box as given.\n"
                 "  Scores: OUT found and its angle error (stage hand - p_uc vs truth wrist - p_uc, p_uc = the stage's own\n"
                 "  shoulder centre); FRONT found and HIGH/LOW right (stage hand - p_bc, y < 0 = HIGH, vs truth wrist\n"
                 "  above/below the torso centre); false hands on REST persons; kind accuracy over scored persons.\n"
                 "  Per-person CSV (--csv), annotated PNGs (--png-dir: skin, hand square, vector, truth arms, person box).\n"
                 "--video FILE|FOLDER (--gesture none | --truth FILE): a real clip (a video file, or a folder of images such as\n"
                 "  an OTB/UAV123 sequence's img/) through the tracker, hands and decide stages as the pipeline runs them (the\n"
                 "  user from the face search, or --init-box x,y,w,h on the first frame as TRACKER_INIT), judged against what\n"
                 "  the person does: no gesture in the whole clip, or --truth lines 'first,last,GESTURE' (0-based frames,\n"
                 "  inclusive; REST OUT UP DOWN CLOSER FURTHER; frames outside every range not judged), from --settle-s\n"
                 "  (0.8) after each change: the right hand (REST none, OUT/UP/DOWN OUT, CLOSER/FURTHER FRONT higher/lower)\n"
                 "  and command per gesture, a moving command where no gesture is made.\n"
                 "  Per-frame CSV (--csv), the pipeline's overlay as an MP4 (--mp4).\n\n" +
                     keypoint_truth_rules());
  SyntheticEvalOptions syn;
  CocoEvalOptions coco;
  VideoEvalOptions video;
  std::string box = "annotation", png_dir, csv_path, method_help;
  bool json = false;
  auto& app = cli.app();
  // Rewritten to --set hands.method=M before parsing (method_as_set): here for --help.
  app.add_option("--method", method_help, "the hands method to score: pose or skin (default: the config's hands.method)");
  auto* scenario_opt = app.add_option("--scenario", syn.scenario, "synthetic mode: scenario name (deploy/scenarios/NAME.yaml) or path");
  auto* seed_opt = app.add_option("--seed", syn.seed, "synthetic mode: world seed");
  auto* stride_opt = app.add_option("--stride", syn.stride, "synthetic mode: score every N-th frame")->check(CLI::PositiveNumber);
  auto* pngs_opt = app.add_option("--pngs", syn.pngs, "synthetic mode: how many annotated PNGs at most")->check(CLI::NonNegativeNumber);
  auto* coco_opt = app.add_option("--coco", coco.annotations, "COCO person-keypoints JSON: real-photo mode")->check(CLI::ExistingFile);
  auto* images_opt = app.add_option("--images", coco.images_dir, "COCO mode: folder of the images")->check(CLI::ExistingDirectory);
  auto* box_opt = app.add_option("--box", box, "COCO mode: user box from the 'annotation' bbox, from the Haar 'face' (as the tracker) or the 'keypoints' face")
                      ->check(CLI::IsMember({"annotation", "face", "keypoints"}));
  app.add_option("--png-dir", png_dir, "folder for annotated PNGs (synthetic default eval_hands_png; COCO: none unless given; '' = none)");
  app.add_option("--csv", csv_path, "write one line per frame (synthetic) or per person (COCO) to this file");
  app.add_flag("--json", json, "print one JSON object on stdout");
  auto* video_opt = app.add_option("--video", video.source, "real-clip mode: a video file or a folder of images")->check(CLI::ExistingPath);
  auto* gesture_opt = app.add_option("--gesture", video.gesture, "video mode: what the person does in the whole clip")
                          ->check(CLI::IsMember({"none"}));
  auto* truth_opt = app.add_option("--truth", video.truth_path, "video mode: gesture truth, lines first,last,GESTURE")->check(CLI::ExistingFile);
  auto* settle_opt = app.add_option("--settle-s", video.settle_s, "video mode: not judged this long after each change, s (default 0.8)")
                         ->check(CLI::NonNegativeNumber);
  truth_opt->excludes(gesture_opt);
  auto* fps_opt = app.add_option("--fps", video.fps, "video mode: frame rate of an image folder (default 25)")->check(CLI::PositiveNumber);
  auto* init_opt = app.add_option("--init-box", video.init_box, "video mode: x,y,w,h of the user on the first frame (default: face search)");
  auto* mp4_opt = app.add_option("--mp4", video.mp4_path, "video mode: annotated MP4 (the pipeline's overlay)");
  for (auto* o : {gesture_opt, truth_opt, settle_opt, fps_opt, init_opt, mp4_opt}) o->needs(video_opt);
  for (auto* o : {scenario_opt, seed_opt, stride_opt, pngs_opt, coco_opt}) o->excludes(video_opt);
  coco_opt->needs(images_opt);
  images_opt->needs(coco_opt);
  box_opt->needs(coco_opt);
  for (auto* o : {scenario_opt, seed_opt, stride_opt, pngs_opt}) o->excludes(coco_opt);

  return cli.run(argc, argv, [&](const Config& config) {
    const bool png_given = app.count("--png-dir") > 0;
    // OpenCV's threads, once for the process: the hands stage's, and the tracker's where its code runs too
    // (--video's tracker, --coco's face search).
    const bool runs_tracker = !video.source.empty() || !coco.annotations.empty();
    set_opencv_threads(fewest_opencv_threads(
        {opencv_threads_of(config, "hands"), runs_tracker ? opencv_threads_of(config, "tracker") : std::nullopt}));
    if (!video.source.empty()) {
      video.csv_path = csv_path;
      video.json = json;
      return run_video_eval(video, config);
    }
    if (coco.annotations.empty()) {
      syn.json = json;
      syn.csv_path = csv_path;
      if (png_given) syn.png_dir = png_dir;
      return run_synthetic_eval(syn, config);
    }
    coco.box = box == "face" ? BoxMode::Face : box == "keypoints" ? BoxMode::Keypoints : BoxMode::Annotation;
    coco.csv_path = csv_path;
    coco.png_dir = png_dir;
    const auto hands = config.section<HandsParams>("hands");
    const std::string box_description = coco.box == BoxMode::Face        ? "body_from_face of the Haar face on the person's head keypoints"
                                        : coco.box == BoxMode::Keypoints ? "body_from_face of the face box the head keypoints span"
                                                                         : "body_from_face of the Haar face in the COCO annotation bbox's re-check window, else that bbox";
    const HandsScoreboard board = run_coco_eval(coco, hands, config.section<TrackerParams>("tracker"));
    if (json) {
      const nlohmann::json context = {{"mode", "coco"},
                                      {"annotations", coco.annotations},
                                      {"images", coco.images_dir},
                                      {"box", box},
                                      {"user_box", box_description},
                                      {"truth", "keypoint_truth rules (gpilot-eval-hands --help)"}};
      std::cout << board.to_json(context).dump() << std::endl;
    } else {
      board.print_table(stdout, "COCO persons of " + coco.annotations + ", box: " + box + " (" + box_description + ")");
      if (!csv_path.empty()) std::printf("per-person CSV              %s\n", csv_path.c_str());
      if (!png_dir.empty()) std::printf("annotated PNGs              %s\n", png_dir.c_str());
    }
    return 0;
  });
}
