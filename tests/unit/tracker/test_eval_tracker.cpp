// Known answers of the tracker evaluation's pieces: OTB scores, box parsing, OTB folders (1-based boxes)
// and LCM logs whose CAMERA and GROUND_TRUTH are paired by seq whatever their order.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>

#include "image_codec.hpp"
#include "metrics.hpp"
#include "sequence.hpp"
#include "gpilot/ground_truth_t.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

TEST(EvalMetrics, IouCentreErrorAndScores) {
  EXPECT_DOUBLE_EQ(iou(cv::Rect2d(0, 0, 10, 10), cv::Rect2d(5, 0, 10, 10)), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(iou(cv::Rect2d(0, 0, 10, 10), cv::Rect2d(20, 0, 10, 10)), 0.0);
  EXPECT_DOUBLE_EQ(centre_error(cv::Rect2d(0, 0, 10, 10), cv::Rect2d(3, 4, 10, 10)), 5.0);
  // IoUs 1, 0.5, 0: success above thresholds 0..1 step 0.05.
  const TrackScores s = score({1.0, 0.5, 0.0}, {0.0, 20.0, 25.0});
  EXPECT_DOUBLE_EQ(s.success[0], 2.0 / 3.0);    // IoU > 0
  EXPECT_DOUBLE_EQ(s.success[10], 1.0 / 3.0);   // IoU > 0.5: only the perfect frame
  EXPECT_DOUBLE_EQ(s.success[20], 0.0);         // IoU > 1: none
  // Rates: thresholds 0..0.45 (10 of them) 2/3, 0.5..0.95 (10) 1/3, 1.0 none -> AUC = (20/3 + 10/3) / 21.
  EXPECT_NEAR(s.success_auc, 10.0 / 21.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.precision_20px, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.mean_iou, 0.5);
}

TEST(EvalSequence, ParsesBoxesAndRejectsBadLines) {
  ASSERT_TRUE(parse_box("1,2,3,4").has_value());
  EXPECT_EQ(*parse_box("1\t2\t3\t4"), cv::Rect2d(1, 2, 3, 4));
  EXPECT_FALSE(parse_box("1,2,3").has_value());
  EXPECT_FALSE(parse_box("1,2,0,4").has_value());
  EXPECT_FALSE(parse_box("a,b,c,d").has_value());
  EXPECT_FALSE(parse_box("NaN,NaN,NaN,NaN").has_value());
  EXPECT_TRUE(is_absent_line("NaN,NaN,NaN,NaN"));
  EXPECT_TRUE(is_absent_line("nan\tnan\tnan\tnan\r"));
  EXPECT_FALSE(is_absent_line("NaN,NaN,NaN"));
  EXPECT_FALSE(is_absent_line("1,NaN,NaN,NaN"));
}

// UAV123 marks frames without a visible target "NaN,NaN,NaN,NaN": no truth there, and the frame says so.
TEST(EvalSequence, OtbFolderNanLineIsAnAbsentTarget) {
  const fs::path dir = fs::temp_directory_path() / "gpilot_eval_otb_nan_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "img");
  for (int i = 1; i <= 3; ++i)
    cv::imwrite((dir / "img" / ("000" + std::to_string(i) + ".jpg")).string(), cv::Mat(20, 30, CV_8UC3, cv::Scalar(i)));
  std::ofstream(dir / "groundtruth_rect.txt") << "11,21,5,6\nNaN,NaN,NaN,NaN\n12,22,5,6\n";
  auto src = open_otb(dir.string());
  EvalFrame f;
  ASSERT_TRUE(src->next(f));
  EXPECT_FALSE(f.absent);
  ASSERT_TRUE(src->next(f));
  EXPECT_TRUE(f.absent);
  EXPECT_FALSE(f.truth.has_value());
  ASSERT_TRUE(src->next(f));
  EXPECT_FALSE(f.absent);
  EXPECT_EQ(*f.truth, cv::Rect2d(11, 21, 5, 6));
  fs::remove_all(dir);
}

// Frames: visible, absent x2 (lost on one), visible (IoU 0.2, 0.6) -> re-found 1 visible frame after the
// return; absent again at the end is a reappearance that never comes (none pushed).
TEST(EvalMetrics, AbsenceBehaviourCountsLostReportsAndRefindDelays) {
  const std::vector<FrameVerdict> v = {{false, true, 0.8}, {true, false, 0.0}, {true, true, 0.0}, {false, true, 0.2},
                                       {false, true, 0.6}, {true, true, 0.0},  {false, false, 0.7}, {false, true, 0.1}};
  const AbsenceBehaviour b = absence_behaviour(v);
  EXPECT_EQ(b.absent_frames, 3);
  EXPECT_EQ(b.reported_lost, 1);
  // Second reappearance: the tracker reported no box on the first visible frame, then IoU 0.1: never.
  EXPECT_EQ(b.refound_after, (std::vector<int>{1, -1}));
  EXPECT_TRUE(absence_behaviour({{false, true, 1.0}}).refound_after.empty());
}

TEST(EvalSequence, OtbFolderBoxesAreMadeZeroBased) {
  const fs::path dir = fs::temp_directory_path() / "gpilot_eval_otb_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "img");
  for (int i = 1; i <= 2; ++i)
    cv::imwrite((dir / "img" / ("000" + std::to_string(i) + ".jpg")).string(), cv::Mat(20, 30, CV_8UC3, cv::Scalar(i)));
  std::ofstream(dir / "groundtruth_rect.txt") << "11,21,5,6\n12,22,5,6\n";
  auto src = open_otb(dir.string());
  EvalFrame f;
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(*f.truth, cv::Rect2d(10, 20, 5, 6));
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(*f.truth, cv::Rect2d(11, 21, 5, 6));
  EXPECT_FALSE(src->next(f));
  std::ofstream(dir / "groundtruth_rect.txt") << "11,21,5\n";
  EXPECT_THROW(open_otb(dir.string()), std::runtime_error);
  EXPECT_THROW(open_otb((dir / "missing").string()), std::runtime_error);
  fs::remove_all(dir);
}

TEST(EvalSequence, LogPairsCameraAndGroundTruthBySeq) {
  const fs::path path = fs::temp_directory_path() / "gpilot_eval_log_test.lcmlog";
  {
    lcm::LogFile log(path.string(), "w");
    ASSERT_TRUE(log.good());
    int64_t n = 0;
    auto write = [&](const std::string& channel, const auto& msg) {
      std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
      msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
      lcm::LogEvent ev{};
      ev.eventnum = n;
      ev.timestamp = 1000 * n++;
      ev.channel = channel;
      ev.datalen = static_cast<int32_t>(buf.size());
      ev.data = buf.data();
      log.writeEvent(&ev);
    };
    auto truth = [](int64_t seq) {
      ground_truth_t g{};
      g.seq = seq;
      g.user_box[0] = 10.0f * static_cast<float>(seq);
      g.user_box[1] = 5;
      g.user_box[2] = 8;
      g.user_box[3] = 9;
      return g;
    };
    // Frame 0 then its truth; truth 1 before frame 1; frame 2 with no truth at all; junk on CAMERA.
    write("CAMERA", mat_to_image(cv::Mat(20, 30, CV_8UC3, cv::Scalar(0)), 0, 0));
    write("GROUND_TRUTH", truth(0));
    write("GROUND_TRUTH", truth(1));
    write("CAMERA", mat_to_image(cv::Mat(20, 30, CV_8UC3, cv::Scalar(1)), 1, 1));
    write("CAMERA", mat_to_image(cv::Mat(20, 30, CV_8UC3, cv::Scalar(2)), 2, 2));
    write("OTHER", truth(7));
  }
  auto src = open_lcm_log(path.string());
  EvalFrame f;
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 0);
  EXPECT_EQ(*f.truth, cv::Rect2d(0, 5, 8, 9));
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 1);
  EXPECT_EQ(*f.truth, cv::Rect2d(10, 5, 8, 9));
  ASSERT_TRUE(src->next(f));
  EXPECT_EQ(f.image.at<cv::Vec3b>(0, 0)[0], 2);
  EXPECT_FALSE(f.truth.has_value());
  EXPECT_FALSE(src->next(f));
  fs::remove(path);
  EXPECT_THROW(open_lcm_log("/nonexistent.lcmlog"), std::runtime_error);
}

#ifdef GPILOT_HAVE_SYNTHETIC
// --synthetic-truth face: the head's box where the face shows (a head annotated as OTB's face clips are), no
// truth and the frame absent while the back is turned.
TEST(EvalSequence, SyntheticFaceTruthIsTheFaceBoxAndAbsentWithTheBackTurned) {
  auto users = open_synthetic("idle");
  auto faces = open_synthetic("idle", SyntheticTruthBox::kFace);
  EvalFrame u, f;
  ASSERT_TRUE(users->next(u));
  ASSERT_TRUE(faces->next(f));
  ASSERT_TRUE(u.truth && f.truth);
  EXPECT_FALSE(f.absent);
  EXPECT_EQ((*u.truth & *f.truth), *f.truth);  // the face inside the body box, a third of its width
  EXPECT_NEAR(f.truth->width / u.truth->width, 1.0 / 2.75, 0.05);
  auto turning = open_synthetic("turn-around", SyntheticTruthBox::kFace);
  int frame = 0, first_absent = -1;
  while (first_absent < 0 && turning->next(f) && ++frame < 400)
    if (f.absent) {
      first_absent = frame;
      EXPECT_FALSE(f.truth.has_value());
    }
  // The back is to the camera from about 10.6 s (25 frames a second).
  EXPECT_GT(first_absent, 240);
  EXPECT_LT(first_absent, 290);
}
#endif

}  // namespace
}  // namespace gpilot
