// gpilot-eval-skin: scores a skin model on labelled data: precision, recall, F1 at the configured threshold
// (hands.skin.threshold), the best-F1 threshold, the ROC curve (PNG) and its area.
#include <algorithm>
#include <cstdio>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hands/hands_params.hpp"
#include "hands/skin_adapter.hpp"
#include "hands/skin_data.hpp"
#include "hands/skin_model.hpp"
#include "json_out.hpp"
#include "log.hpp"
#include "paths.hpp"
#include "service_cli.hpp"

using namespace gpilot;

namespace {

json rounded4(double v) { return rounded(v, 4); }  // the table's digits

void write_roc_png(const std::string& path, const LevelCounts& counts, const LevelCounts::Score& at, const std::string& title) {
  const int size = 480, margin = 50;
  cv::Mat img(size + 2 * margin, size + 2 * margin, CV_8UC3, cv::Scalar(255, 255, 255));
  auto pt = [&](double fpr, double tpr) {
    return cv::Point(margin + static_cast<int>(fpr * size), margin + size - static_cast<int>(tpr * size));
  };
  for (int i = 0; i <= 10; ++i) {
    cv::line(img, pt(i / 10.0, 0), pt(i / 10.0, 1), cv::Scalar(230, 230, 230));
    cv::line(img, pt(0, i / 10.0), pt(1, i / 10.0), cv::Scalar(230, 230, 230));
  }
  cv::rectangle(img, pt(0, 1), pt(1, 0), cv::Scalar(0, 0, 0));
  cv::line(img, pt(0, 0), pt(1, 1), cv::Scalar(180, 180, 180));
  const auto roc = counts.roc();
  for (size_t i = 1; i < roc.size(); ++i)
    cv::line(img, pt(roc[i - 1].false_positive_rate, roc[i - 1].recall), pt(roc[i].false_positive_rate, roc[i].recall),
             cv::Scalar(200, 60, 0), 2, cv::LINE_AA);
  cv::circle(img, pt(at.false_positive_rate, at.recall), 6, cv::Scalar(0, 0, 220), 2, cv::LINE_AA);
  const auto font = cv::FONT_HERSHEY_SIMPLEX;
  cv::putText(img, title, cv::Point(margin, 30), font, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  char buf[200];
  std::snprintf(buf, sizeof buf, "AUC %.4f  threshold %.2f: P %.3f R %.3f F1 %.3f", counts.auc(), at.threshold, at.precision,
                at.recall, at.f1);
  cv::putText(img, buf, cv::Point(margin + 10, margin + size - 15), font, 0.45, cv::Scalar(0, 0, 180), 1, cv::LINE_AA);
  cv::putText(img, "false positive rate", cv::Point(margin + size / 2 - 70, margin + size + 35), font, 0.5, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  cv::putText(img, "TPR", cv::Point(8, margin + size / 2), font, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  if (!cv::imwrite(path, img)) throw std::runtime_error("cannot write " + path);
}

// Pixel counts of a binary classifier against a mask (mask_label: skin, not, ignore).
struct Confusion {
  int64_t tp = 0, fp = 0, fn = 0, tn = 0;
  void add(const SkinClassifier& c, const cv::Mat& bgr, const cv::Mat& mask, const cv::Rect& skip) {
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x) {
        if (skip.contains({x, y})) continue;
        const MaskLabel label = mask_label(mask.at<uint8_t>(y, x));
        if (label == MaskLabel::Ignore) continue;
        const auto& p = bgr.at<cv::Vec3b>(y, x);
        const bool said = c.is_skin(p[0], p[1], p[2]), truth = label == MaskLabel::Skin;
        (said ? (truth ? tp : fp) : (truth ? fn : tn)) += 1;
      }
  }
  double precision() const { return tp + fp ? static_cast<double>(tp) / static_cast<double>(tp + fp) : 0; }
  double recall() const { return tp + fn ? static_cast<double>(tp) / static_cast<double>(tp + fn) : 0; }
  double f1() const { return precision() + recall() > 0 ? 2 * precision() * recall() / (precision() + recall()) : 0; }
};

// --adapt on one image: the "face" is a square of side 0.2 x the shorter image side on the skin pixel nearest
// the skin centroid (where a face detector would hand over the user's skin); the "user box" is the skin's
// bounding box, the scene everything outside it. Both classifiers are scored on every pixel but the face square.
void add_adapted(const SkinParams& params, const SkinModel& model, const cv::Mat& bgr, const cv::Mat& mask, Confusion& fixed,
                 Confusion& adapted, int64_t& faces) {
  std::vector<cv::Point> skin;
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x)
      if (mask_label(mask.at<uint8_t>(y, x)) == MaskLabel::Skin) skin.emplace_back(x, y);
  SkinAdapter adapter(params, model);
  cv::Rect face;
  if (!skin.empty()) {
    cv::Point2d c(0, 0);
    for (const auto& p : skin) c += cv::Point2d(p);
    c *= 1.0 / static_cast<double>(skin.size());
    const auto at = *std::min_element(skin.begin(), skin.end(), [&](const cv::Point& a, const cv::Point& b) {
      return cv::norm(cv::Point2d(a) - c) < cv::norm(cv::Point2d(b) - c);
    });
    const int side = std::max(4, std::min(bgr.cols, bgr.rows) / 5);
    face = cv::Rect(at.x - side / 2, at.y - side / 2, side, side) & cv::Rect(0, 0, bgr.cols, bgr.rows);
    adapter.learn_user(bgr, cv::Rect2f(face));
    adapter.learn_scene(bgr, cv::boundingRect(skin));
    faces += adapter.user_samples() > 0;
  }
  fixed.add(SkinClassifier(model, params.threshold), bgr, mask, face);
  adapted.add(adapter.classifier_for_frame(), bgr, mask, face);
}

}  // namespace

int main(int argc, char** argv) {
  ServiceCli cli("gpilot-eval-skin",
                 "Scores a skin model on labelled data: precision, recall and F1 at the threshold, the ROC curve (PNG).\n"
                 "Data: --pixels FILE (UCI layout: B G R label, 1 = skin, 2 = not) or --images DIR --masks DIR (paired by\n"
                 "file stem; mask 255 = skin, 0 = not, exactly 128 = ignore, other values skin when > 128).");
  std::string pixels, images, masks, model_path, roc_png;
  double threshold = -1;
  bool json = false, adapt = false;
  auto& app = cli.app();
  app.add_option("--pixels", pixels, "labelled pixel file (UCI layout)")->check(CLI::ExistingFile);
  app.add_option("--images", images, "image folder")->check(CLI::ExistingDirectory);
  app.add_option("--masks", masks, "mask folder")->check(CLI::ExistingDirectory);
  app.add_option("--model", model_path, "model file (default: hands.skin.model of the config)");
  app.add_option("--threshold", threshold, "P(skin) threshold (default: hands.skin.threshold of the config)")->check(CLI::Range(0.0, 1.0));
  app.add_option("--roc", roc_png, "write the ROC curve to this PNG");
  app.add_flag("--json", json, "print one JSON object on stdout");
  app.add_flag("--adapt", adapt,
               "with --images/--masks: the skin model that learns the user and the scene (hands.skin.adapt), per image:\n"
               "the user from a face-sized square on the skin nearest its centroid, the scene from outside the skin's\n"
               "bounding box; precision/recall/F1 of the table alone and adapted on the same pixels (the square excluded)");
  return cli.run(argc, argv, [&](const Config& config) {
    if (adapt && images.empty()) {
      log_error("--adapt needs --images DIR --masks DIR");
      return 2;
    }
    if (pixels.empty() == images.empty() || images.empty() != masks.empty()) {
      log_error("give either --pixels FILE or --images DIR --masks DIR");
      return 2;
    }
    const auto params = config.section<HandsParams>("hands");
    if (model_path.empty()) model_path = resolve_project_path(params.skin.model);
    if (threshold < 0) threshold = params.skin.threshold;
    const SkinModel model = SkinModel::load(model_path);
    if (adapt) {
      SkinParams sp = params.skin;
      sp.threshold = threshold;
      sp.adapt.enabled = true;
      Confusion fixed, adapted;
      int64_t faces = 0;
      const auto pairs = pair_images_and_masks(images, masks);
      for (size_t i = 0; i < pairs.size(); ++i) {
        cv::Mat bgr, mask;
        read_pair(pairs[i], bgr, mask);
        add_adapted(sp, model, bgr, mask, fixed, adapted, faces);
        if ((i + 1) % 50 == 0 || i + 1 == pairs.size()) std::fprintf(stderr, "\r%zu/%zu images", i + 1, pairs.size());
      }
      std::fprintf(stderr, "\n");
      if (json) {
        const gpilot::json out = {{"model", model_path},
                          {"data", images},
                          {"images", pairs.size()},
                          {"threshold", rounded4(threshold)},
                          {"users_learnt", faces},
                          {"table", {{"precision", rounded4(fixed.precision())}, {"recall", rounded4(fixed.recall())}, {"f1", rounded4(fixed.f1())}}},
                          {"adapted", {{"precision", rounded4(adapted.precision())}, {"recall", rounded4(adapted.recall())},
                                       {"f1", rounded4(adapted.f1())}}}};
        std::printf("%s\n", out.dump().c_str());
      } else {
        std::printf("model      %s\ndata       %s (%zu images, user learnt on %lld)\nthreshold  %.3f\n\n", model_path.c_str(),
                    images.c_str(), pairs.size(), static_cast<long long>(faces), threshold);
        std::printf("%-10s %10s %10s %10s\n", "", "precision", "recall", "F1");
        std::printf("%-10s %10.4f %10.4f %10.4f\n", "table", fixed.precision(), fixed.recall(), fixed.f1());
        std::printf("%-10s %10.4f %10.4f %10.4f\n", "adapted", adapted.precision(), adapted.recall(), adapted.f1());
      }
      return 0;
    }
    LevelCounts counts;
    std::string data;
    if (!pixels.empty()) {
      counts.add_pixels(model, read_uci_pixels(pixels));
      data = pixels;
    } else {
      const auto pairs = pair_images_and_masks(images, masks);
      for (size_t i = 0; i < pairs.size(); ++i) {
        cv::Mat bgr, mask;
        read_pair(pairs[i], bgr, mask);
        counts.add_image(model, bgr, mask);
        if ((i + 1) % 100 == 0 || i + 1 == pairs.size()) std::fprintf(stderr, "\r%zu/%zu images", i + 1, pairs.size());
      }
      std::fprintf(stderr, "\n");
      data = images + " (" + std::to_string(pairs.size()) + " images)";
    }
    const auto at = counts.score(threshold);
    LevelCounts::Score best;
    for (const auto& s : counts.roc())
      if (s.f1 > best.f1) best = s;
    if (!roc_png.empty()) write_roc_png(roc_png, counts, at, data);
    if (json) {
      const gpilot::json out = {{"model", model_path},
                        {"data", data},
                        {"threshold", rounded4(at.threshold)},
                        {"precision", rounded4(at.precision)},
                        {"recall", rounded4(at.recall)},
                        {"f1", rounded4(at.f1)},
                        {"false_positive_rate", rounded4(at.false_positive_rate)},
                        {"auc", rounded4(counts.auc())},
                        {"skin_pixels", counts.skin_total()},
                        {"non_skin_pixels", counts.non_skin_total()},
                        {"best_f1", rounded4(best.f1)},
                        {"best_f1_threshold", rounded4(best.threshold)}};
      std::printf("%s\n", out.dump().c_str());
    } else {
      std::printf("model      %s\ndata       %s\npixels     %lld skin, %lld not skin\n", model_path.c_str(), data.c_str(),
                  static_cast<long long>(counts.skin_total()), static_cast<long long>(counts.non_skin_total()));
      std::printf("threshold  %.3f\nprecision  %.4f\nrecall     %.4f\nF1         %.4f\nFPR        %.4f\nROC AUC    %.4f\n",
                  at.threshold, at.precision, at.recall, at.f1, at.false_positive_rate, counts.auc());
      std::printf("(best F1 on this data %.4f at threshold %.3f: for information, not for choosing the threshold)\n", best.f1,
                  best.threshold);
    }
    return 0;
  });
}
