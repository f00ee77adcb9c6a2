// gpilot-skin-train: builds the histogram skin model (P(skin | B,G,R) table) from labelled pixels and/or
// image+mask folders and writes the model file gpilot-hands loads (hands.skin.model).
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "hands/skin_data.hpp"
#include "hands/skin_model.hpp"
#include "log.hpp"
#include "service_cli.hpp"

using namespace gpilot;

int main(int argc, char** argv) {
  CLI::App app(
      "Trains the nonparametric histogram skin model (Conaire 2007 style: RGB -> one index -> P(skin), Bayes with\n"
      "the class priors from the counts, Gaussian smoothing of the counts) and writes the model file.\n"
      "Sources: --pixels (UCI layout: B G R label, 1 = skin, 2 = not) and/or --images/--masks folder pairs\n"
      "(paired by file stem; mask 255 = skin, 0 = not, 128 = ignore, other values skin when > 128).",
      "gpilot-skin-train");
  std::vector<std::string> pixel_files, image_dirs, mask_dirs;
  std::string out;
  int bins = 32;
  double sigma = 1.0, image_weight = 1.0;
  app.add_option("--pixels", pixel_files, "labelled pixel file(s), UCI layout")->check(CLI::ExistingFile);
  app.add_option("--images", image_dirs, "image folder(s); each pairs with the --masks folder at the same position");
  app.add_option("--masks", mask_dirs, "mask folder(s)");
  app.add_option("--image-weight", image_weight, "weight of one image pixel against one --pixels pixel")->check(CLI::PositiveNumber);
  app.add_option("--bins", bins, "histogram bins per channel (power of two)")->check(CLI::Range(2, 256));
  app.add_option("--sigma", sigma, "Gaussian smoothing of the counts, in bins (0 = none)")->check(CLI::Range(0.0, 16.0));
  app.add_option("--out", out, "model file to write (YAML)")->required();
  std::string log_level;
  add_standard_flags(app, "gpilot-skin-train", log_level);
  CLI11_PARSE(app, argc, argv);
  if (!apply_log_level(log_level)) return 2;
  if (pixel_files.empty() && image_dirs.empty()) {
    log_error("give --pixels and/or --images/--masks");
    return 2;
  }
  if (image_dirs.size() != mask_dirs.size()) {
    log_error("each --images folder needs one --masks folder");
    return 2;
  }
  try {
    SkinHistogram hist(bins);
    std::ostringstream how;
    how << "bins " << bins << " per channel (B,G,R), Gaussian smoothing sigma " << sigma << " bins, priors from counts\n";
    for (const auto& f : pixel_files) {
      const auto px = read_uci_pixels(f);
      int64_t skin = 0;
      for (const auto& p : px) {
        hist.add(p.b, p.g, p.r, p.skin);
        skin += p.skin;
      }
      how << "pixels " << f << ": " << skin << " skin, " << px.size() - static_cast<size_t>(skin) << " not\n";
      log_info("%s: %zu pixels", f.c_str(), px.size());
    }
    for (size_t d = 0; d < image_dirs.size(); ++d) {
      const auto pairs = pair_images_and_masks(image_dirs[d], mask_dirs[d]);
      int64_t skin = 0, non = 0;
      for (size_t i = 0; i < pairs.size(); ++i) {
        cv::Mat bgr, mask;
        read_pair(pairs[i], bgr, mask);
        for (int y = 0; y < bgr.rows; ++y)
          for (int x = 0; x < bgr.cols; ++x) {
            const MaskLabel label = mask_label(mask.at<uint8_t>(y, x));
            if (label == MaskLabel::Ignore) continue;
            const auto& c = bgr.at<cv::Vec3b>(y, x);
            hist.add(c[0], c[1], c[2], label == MaskLabel::Skin, image_weight);
            (label == MaskLabel::Skin ? skin : non) += 1;
          }
        if ((i + 1) % 100 == 0) log_info("%s: %zu/%zu images", image_dirs[d].c_str(), i + 1, pairs.size());
      }
      how << "images " << image_dirs[d] << " (" << pairs.size() << " with masks): " << skin << " skin, " << non
          << " not, weight " << image_weight << "\n";
    }
    SkinTrainOptions opt;
    opt.smoothing_sigma = sigma;
    opt.description = how.str();
    const SkinModel model = SkinModel::train(hist, opt);
    model.save(out);
    log_info("wrote %s (%d^3 bins)\n%s", out.c_str(), bins, opt.description.c_str());
  } catch (const std::exception& e) {
    log_error("%s", e.what());
    return 1;
  }
  return 0;
}
