#include "coco_eval.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "coco_keypoints.hpp"
#include "hands/hands_core_factory.hpp"
#include "log.hpp"
#include "hands/hand_overlay.hpp"
#include "person_csv.hpp"
#include "truth_overlay.hpp"

namespace gpilot {

namespace {

std::string png_name(const CocoImage& im, int64_t annotation_id, BoxMode mode) {
  const std::string stem = std::filesystem::path(im.file_name).stem().string();
  return stem + "_" + std::to_string(annotation_id) + "_" + box_mode_name(mode) + ".png";
}

}  // namespace

HandsScoreboard run_coco_eval(const CocoEvalOptions& o, const HandsParams& hands, const TrackerParams& tracker) {
  const CocoKeypointFile coco = CocoKeypointFile::load(o.annotations);
  const auto method = make_hand_method(hands);
  UserViewChooser chooser(tracker, o.box);
  std::unique_ptr<PersonCsv> csv;
  if (!o.csv_path.empty()) csv = std::make_unique<PersonCsv>(o.csv_path);
  if (!o.png_dir.empty()) std::filesystem::create_directories(o.png_dir);

  HandsScoreboard board;
  int32_t track_id = 0;
  size_t image_no = 0, images_with_people = 0, images_loaded = 0;
  std::string first_missing;
  for (const CocoImage& im : coco.images()) {
    ++image_no;
    std::vector<const CocoAnnotation*> people;
    for (const CocoAnnotation& a : coco.annotations())
      if (a.image_id == im.id) people.push_back(&a);
    if (people.empty()) continue;
    const std::string path = (std::filesystem::path(o.images_dir) / im.file_name).string();
    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    ++images_with_people;
    if (!bgr.empty()) ++images_loaded;
    else if (first_missing.empty()) first_missing = path;
    if (o.progress)
      std::fprintf(stderr, "[%zu/%zu] %s: %zu persons%s\n", image_no, coco.images().size(), im.file_name.c_str(), people.size(),
                   bgr.empty() ? " (image does not load: skipped)" : "");
    if (!bgr.empty() && (bgr.cols != im.width || bgr.rows != im.height))
      log_warn("%s is %dx%d, the annotations say %dx%d", path.c_str(), bgr.cols, bgr.rows, im.width, im.height);

    for (const CocoAnnotation* a : people) {
      board.add_read();
      PersonCsvRow row;
      row.image = im.file_name;
      row.annotation_id = a->id;
      row.box_mode = box_mode_name(o.box);
      row.box = a->bbox;
      if (bgr.empty()) {
        board.add_image_unreadable();
        row.status = "image_unreadable";
        row.note = path;
        if (csv) csv->write(row);
        continue;
      }
      const PersonKeypointTruth truth = keypoint_truth(BodyKeypoints::from([&](const std::string& name) -> std::optional<BodyPoint> {
        const auto k = coco.keypoint(*a, name);
        if (!k) return std::nullopt;
        return BodyPoint{k->p, k->v};
      }));
      row.truth = &truth;
      if (!truth.usable) {
        board.add_skipped_not_visible();
        row.status = "skipped_not_visible";
        row.note = truth.skip_reason;
        if (csv) csv->write(row);
        continue;
      }
      board.add_truth(truth);
      const ChosenView view = chooser.choose(bgr, a->bbox, truth, ++track_id);
      row.face = view.face;
      row.note = view.note;
      if (view.face) board.add_face_found();
      std::optional<HandsOutput> result;
      std::optional<PersonScore> score;
      if (!view.view) {
        board.add_no_face(truth.person);
        row.status = "no_face";
      } else {
        method->reset();
        result = method->observe(bgr, *view.view, 0);  // one photo: no time
        score = score_person(truth, *result, bgr, result->skin ? result->skin->classifier : nullptr, &hands);
        board.add_run(truth, *result, *score);
        row.status = result->refused.empty() ? "run" : "colourless";
        row.box = view.view->box;
        row.result = &*result;
        row.score = &*score;
      }
      if (csv) csv->write(row);
      if (!o.png_dir.empty()) {
        cv::Mat img = bgr.clone();
        if (result) draw_hand_overlay(img, *result);
        char caption[256];
        std::snprintf(caption, sizeof caption, "%s #%lld  box %s\ntruth %s (L %s, R %s)  stage %s%s%s", im.file_name.c_str(),
                      static_cast<long long>(a->id), box_mode_name(o.box), person_truth_name(truth.person), arm_truth_name(truth.left.label),
                      arm_truth_name(truth.right.label), result ? hand_kind_name(result->kind) : "not run",
                      view.note.empty() ? "" : "\n", view.note.c_str());
        draw_keypoint_truth(img, truth, a->bbox, view.face, caption);
        cv::imwrite((std::filesystem::path(o.png_dir) / png_name(im, a->id, o.box)).string(), img);
      }
    }
  }
  // Not one image: the wrong folder, not a data set whose every person is unreadable.
  if (images_with_people > 0 && images_loaded == 0)
    throw std::runtime_error("none of the " + std::to_string(images_with_people) + " images with persons in " + o.annotations +
                             " loads from " + o.images_dir + " (first: " + first_missing + ")");
  return board;
}

}  // namespace gpilot
