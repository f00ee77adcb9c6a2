// Skin model: Bayes table from counts, file round trip, labelled-data readers and scores, and the committed
// model's F1 on photographs from a source it was not trained on (abd_skin; skipped without ../shared).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <opencv2/core.hpp>

#include "hands/hands_params.hpp"
#include "hands/skin_data.hpp"
#include "hands/skin_model.hpp"
#include "paths.hpp"

using namespace gpilot;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("gpilot_test_skin_" + name)).string();
}

std::string shared_dir() { return GPILOT_SHARED_DIR; }

}  // namespace

TEST(SkinModel, BayesWithPriorsFromCounts) {
  // bins 4 (shift 6). Colour A: 3 skin. Colour B: 5 non-skin. Colour C's bin: 1 skin, 3 non-skin.
  SkinHistogram h(4);
  for (int i = 0; i < 3; ++i) h.add(10, 10, 200, true);
  for (int i = 0; i < 5; ++i) h.add(200, 200, 10, false);
  h.add(100, 100, 100, true);
  for (int i = 0; i < 3; ++i) h.add(120, 120, 120, false);  // same bin as (100,100,100)
  const SkinModel m = SkinModel::train(h, {0.0, "test"});
  EXPECT_EQ(m.level(10, 10, 200), 255);
  EXPECT_EQ(m.level(63, 63, 255), 255);  // same bin
  EXPECT_EQ(m.level(200, 200, 10), 0);
  // P(skin|c) = (1/4 * 4/12) / (1/4 * 4/12 + 3/8 * 8/12) = 1/4 -> 63.75 -> 64
  EXPECT_EQ(m.level(100, 100, 100), 64);
  EXPECT_EQ(m.level(0, 0, 0), 0);  // never seen
  EXPECT_EQ(h.index(100, 100, 100), (1 * 4 + 1) * 4 + 1);
}

TEST(SkinModel, SmoothingSpreadsIntoEmptyNeighbours) {
  SkinHistogram h(32);
  h.add(128, 128, 128, true);
  h.add(0, 0, 0, false);
  const SkinModel raw = SkinModel::train(h, {0.0, ""});
  const SkinModel smooth = SkinModel::train(h, {1.0, ""});
  EXPECT_EQ(raw.level(136, 128, 128), 0);     // neighbouring bin, empty
  EXPECT_EQ(smooth.level(136, 128, 128), 255);  // only skin mass reaches it
  EXPECT_EQ(smooth.level(255, 255, 255), 0);    // beyond 3 sigma: empty, 0
}

// The blur skips lines of the histogram that are all zero (the learnt ones are sparse); every bin must still be
// what the plain separable definition gives, to the bit: a replay of a live run has to agree bit for bit, and
// a skin decision at its threshold would flip on the last digit.
TEST(SkinModel, SmoothingOfASparseHistogramIsThePlainBlurToTheBit) {
  const int bins = 32;
  const double sigma = 1.0;
  const int radius = 3;
  std::vector<double> kernel;
  double sum = 0;
  for (int k = -radius; k <= radius; ++k) kernel.push_back(std::exp(-0.5 * k * k / (sigma * sigma))), sum += kernel.back();
  for (double& k : kernel) k /= sum;
  cv::RNG rng(7);
  std::vector<double> v(static_cast<size_t>(bins * bins * bins), 0.0);
  for (int i = 0; i < 300; ++i) v[static_cast<size_t>(rng.uniform(0, bins * bins * bins))] += rng.uniform(0.0, 1.0);
  v[0] = 1.0, v.back() = 2.0;  // corners: taps cut by the volume's edge
  std::vector<double> plain = v;
  for (int axis = 0; axis < 3; ++axis) {
    const int stride = axis == 0 ? bins * bins : axis == 1 ? bins : 1;
    std::vector<double> out(plain.size(), 0.0);
    for (int i = 0; i < static_cast<int>(plain.size()); ++i) {
      const int pos = (i / stride) % bins;
      double acc = 0;
      for (int k = -radius; k <= radius; ++k)
        if (pos + k >= 0 && pos + k < bins) acc += kernel[static_cast<size_t>(k + radius)] * plain[static_cast<size_t>(i + k * stride)];
      out[static_cast<size_t>(i)] = acc;
    }
    plain = out;
  }
  const std::vector<double> smooth = smooth_histogram(v, bins, sigma);
  ASSERT_EQ(smooth.size(), plain.size());
  size_t differ = 0, nonzero = 0;
  for (size_t i = 0; i < plain.size(); ++i) differ += smooth[i] != plain[i], nonzero += plain[i] != 0.0;
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(nonzero, 10000u);  // the mass spread: the comparison covers far more than the filled bins
}

TEST(SkinModel, RejectsBadInput) {
  EXPECT_THROW(SkinHistogram(3), SkinModelError);
  SkinHistogram only_skin(8);
  only_skin.add(1, 2, 3, true);
  EXPECT_THROW(SkinModel::train(only_skin, {}), SkinModelError);
  EXPECT_THROW(SkinModel::load(temp_path("missing.yaml")), SkinModelError);
  const std::string bad = temp_path("bad.yaml");
  std::ofstream(bad) << "format: gpilot-skin-histogram-1\nbins: 2\ntable_hex: 00ff00\n";
  EXPECT_THROW(SkinModel::load(bad), SkinModelError);  // 3 entries, 8 needed
  std::ofstream(bad) << "format: something-else\nbins: 2\n";
  EXPECT_THROW(SkinModel::load(bad), SkinModelError);
  std::ofstream(bad) << "format: gpilot-skin-histogram-1\nbins: 2\ntable_hex: 00ff00ff00ff00zz\n";
  EXPECT_THROW(SkinModel::load(bad), SkinModelError);
  std::filesystem::remove(bad);
}

TEST(SkinModel, TrainedThenReloadedGivesIdenticalMasks) {
  cv::RNG rng(7);
  SkinHistogram h(32);
  for (int i = 0; i < 20000; ++i) {
    const int b = rng.uniform(0, 256), g = rng.uniform(0, 256), r = rng.uniform(0, 256);
    h.add(static_cast<uint8_t>(b), static_cast<uint8_t>(g), static_cast<uint8_t>(r), r > g + 20 && g > b);
  }
  const SkinModel trained = SkinModel::train(h, {1.5, "random colours, skin iff r > g + 20 > b + 20"});
  const std::string path = temp_path("roundtrip.yaml");
  trained.save(path);
  const SkinModel loaded = SkinModel::load(path);
  std::filesystem::remove(path);
  EXPECT_EQ(loaded.bins(), 32);
  EXPECT_EQ(loaded.description(), trained.description());
  EXPECT_EQ(loaded.table(), trained.table());
  cv::Mat img(120, 160, CV_8UC3);
  rng.fill(img, cv::RNG::UNIFORM, 0, 256);
  cv::Mat a, b;
  SkinClassifier(trained, 0.5).classify(img, a);
  SkinClassifier(loaded, 0.5).classify(img, b);
  EXPECT_EQ(cv::countNonZero(a != b), 0);
  EXPECT_GT(cv::countNonZero(a), 100);
  EXPECT_GT(cv::countNonZero(a == 0), 100);
  // The classifier agrees with the table and threshold it was made from.
  cv::Mat levels;
  trained.levels(img, levels);
  EXPECT_EQ(cv::countNonZero((levels > SkinModel::threshold_level(0.5)) != (a > 0)), 0);
}

TEST(SkinData, MaskLabels) {
  EXPECT_EQ(mask_label(0), MaskLabel::NotSkin);
  EXPECT_EQ(mask_label(127), MaskLabel::NotSkin);
  EXPECT_EQ(mask_label(128), MaskLabel::Ignore);
  EXPECT_EQ(mask_label(129), MaskLabel::Skin);
  EXPECT_EQ(mask_label(255), MaskLabel::Skin);
}

TEST(SkinData, ReadsUciPixelsAndRejectsMalformedRows) {
  const std::string path = temp_path("pixels.txt");
  std::ofstream(path) << "74\t85\t123\t1\n255 255 255 2\n";
  const auto px = read_uci_pixels(path);
  ASSERT_EQ(px.size(), 2u);
  EXPECT_EQ(px[0].b, 74);
  EXPECT_EQ(px[0].r, 123);
  EXPECT_TRUE(px[0].skin);
  EXPECT_FALSE(px[1].skin);
  std::ofstream(path) << "74 85 123 1\n1 2 3 3\n";
  try {
    read_uci_pixels(path);
    FAIL() << "label 3 accepted";
  } catch (const SkinModelError& e) {
    EXPECT_NE(std::string(e.what()).find(":2:"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "74 85 300 1\n";
  EXPECT_THROW(read_uci_pixels(path), SkinModelError);
  std::filesystem::remove(path);
}

TEST(SkinData, ScoresAtAThreshold) {
  LevelCounts c;
  c.add(255, true);
  c.add(255, true);
  c.add(10, true);
  c.add(200, false);
  c.add(0, false);
  const auto s = c.score(0.5);  // skin iff level > 127: tp 2, fn 1, fp 1, tn 1
  EXPECT_EQ(s.tp, 2);
  EXPECT_EQ(s.fn, 1);
  EXPECT_EQ(s.fp, 1);
  EXPECT_EQ(s.tn, 1);
  EXPECT_DOUBLE_EQ(s.precision, 2.0 / 3);
  EXPECT_DOUBLE_EQ(s.recall, 2.0 / 3);
  EXPECT_DOUBLE_EQ(s.f1, 2.0 / 3);
  EXPECT_DOUBLE_EQ(s.false_positive_rate, 0.5);
  const auto roc = c.roc();
  EXPECT_DOUBLE_EQ(roc.front().recall, 1.0);  // everything skin
  EXPECT_DOUBLE_EQ(roc.back().recall, 0.0);   // nothing skin
  // Pairs (skin, non): 255>200, 255>0, 10>0 right; 10<200 wrong; 255 vs 200 twice right: AUC = 5/6.
  EXPECT_NEAR(c.auc(), 5.0 / 6, 1e-12);
}

TEST(SkinModel, CommittedModelOnUnseenPhotographs) {
  // The committed model is trained on the UCI face pixels only; abd_skin (abdomen photographs, another source)
  // was not used in training, and its train/ half was not looked at while choosing the smoothing. Floors below
  // the measured figures at the configured threshold 0.75 (F1 0.876, precision 0.937, recall 0.822).
  const std::string images = shared_dir() + "/data/skin/abd_skin/train/images";
  if (!std::filesystem::is_directory(images)) GTEST_SKIP() << "needs ../shared/data/skin/abd_skin (not in the repo)";
  const HandsParams p;
  const SkinModel model = SkinModel::load(resolve_project_path(p.skin.model));
  LevelCounts counts;
  for (const auto& pair : pair_images_and_masks(images, shared_dir() + "/data/skin/abd_skin/train/masks")) {
    cv::Mat bgr, mask;
    read_pair(pair, bgr, mask);
    counts.add_image(model, bgr, mask);
  }
  const auto s = counts.score(p.skin.threshold);
  EXPECT_GE(s.f1, 0.86);
  EXPECT_GE(s.precision, 0.92);
  EXPECT_GE(s.recall, 0.80);
}

TEST(SkinModel, CommittedModelIsReproducibleFromUci) {
  // data/skin/README: gpilot-skin-train --pixels Skin_NonSkin.txt --bins 32 --sigma 2 made the committed file.
  const std::string uci = shared_dir() + "/data/skin/uci_skin_segmentation/Skin_NonSkin.txt";
  if (!std::filesystem::exists(uci)) GTEST_SKIP() << "needs ../shared/data/skin/uci_skin_segmentation (or data/skin copy)";
  SkinHistogram h(32);
  for (const auto& px : read_uci_pixels(uci)) h.add(px.b, px.g, px.r, px.skin);
  const SkinModel retrained = SkinModel::train(h, {2.0, ""});
  const SkinModel committed = SkinModel::load(resolve_project_path(HandsParams{}.skin.model));
  EXPECT_EQ(retrained.table(), committed.table());
  EXPECT_EQ(retrained.skin_likelihood(), committed.skin_likelihood());
  EXPECT_EQ(retrained.non_likelihood(), committed.non_likelihood());
  EXPECT_NEAR(retrained.skin_prior(), committed.skin_prior(), 1e-12);
}
