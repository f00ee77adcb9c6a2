// The face's body box checked against the image before a track starts (issue 13): known answers on drawn
// people (a face near the bottom edge, a body narrower / wider / shorter than the preset ratios, a face on a
// poster or a shirt) and on the photographs of data/people; the tracker refuses such faces (counted) and
// keeps searching.
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "body_fit.hpp"
#include "face_cascade.hpp"
#include "face_detector.hpp"
#include "known_scene.hpp"
#include "user_tracker.hpp"

namespace gpilot {
namespace {

const cv::Scalar kSkin(120, 150, 200), kShirt(40, 60, 170), kTrousers(90, 60, 40);

// A drawn person on a textured background: face (fw x fh) with its top-left at `face_tl`, torso and arms
// `body_w_in_faces` face widths wide from the chin to `waist_in_faces` face heights below the face top, legs
// from there to `feet_in_faces` face heights below the face top (two legs 0.45 face widths apart).
struct Drawn {
  cv::Mat img;
  cv::Rect2d face;
};
Drawn draw_person(cv::Size frame, cv::Point2d face_tl, double fw, double body_w_in_faces, double feet_in_faces,
                  double waist_in_faces = 3.5, double body_dx_in_faces = 0.0) {
  Drawn d;
  d.img = test::texture(frame, 7);
  // The background kept away from the clothes' colours (a grey-green texture), as most scenes are.
  d.img.forEach<cv::Vec3b>([](cv::Vec3b& p, const int*) { p = cv::Vec3b(p[0] / 3 + 80, p[1] / 3 + 100, p[1] / 3 + 80); });
  const double fh = fw * 1.0, fx = face_tl.x + fw / 2, cx = fx + body_dx_in_faces * fw;  // face, body centres
  d.face = cv::Rect2d(face_tl.x, face_tl.y, fw, fh);
  const double bw = body_w_in_faces * fw;
  const auto rect = [](double x0, double y0, double x1, double y1) {
    return cv::Rect(cv::Point(static_cast<int>(std::lround(x0)), static_cast<int>(std::lround(y0))),
                    cv::Point(static_cast<int>(std::lround(x1)), static_cast<int>(std::lround(y1))));
  };
  const double chin = face_tl.y + fh, waist = face_tl.y + waist_in_faces * fh, feet = face_tl.y + feet_in_faces * fh;
  cv::rectangle(d.img, rect(cx - 0.2 * fw, chin - 1, cx + 0.2 * fw, chin + 0.3 * fh), kSkin, cv::FILLED);  // neck
  cv::rectangle(d.img, rect(cx - bw / 2, chin + 0.2 * fh, cx + bw / 2, waist), kShirt, cv::FILLED);
  cv::rectangle(d.img, rect(cx - 0.55 * fw, waist, cx - 0.1 * fw, feet), kTrousers, cv::FILLED);
  cv::rectangle(d.img, rect(cx + 0.1 * fw, waist, cx + 0.55 * fw, feet), kTrousers, cv::FILLED);
  cv::ellipse(d.img, cv::Point2d(fx, face_tl.y + fh / 2), cv::Size2d(fw / 2, fh / 2), 0, 0, 360, kSkin, cv::FILLED);
  return d;
}

cv::Mat photo(const std::string& name) {
  return cv::imread(std::string(GPILOT_SOURCE_DIR) + "/data/people/" + name, cv::IMREAD_COLOR);
}

const BodyProportions kPreset = TrackerParams{}.body();

// The preset box of a face w px wide is 2.75 w wide, its top 0.25 face heights above the face top, 7 face
// heights tall; a chest silhouette 0.75 of that (2.06 face widths) is a person of the preset's width.
TEST(BodyFit, PersonAsThePresetKeepsThePresetBox) {
  // GIVEN a person 2.06 face widths wide whose feet are where the preset box ends (6.75 face heights below the face top)
  const Drawn d = draw_person({640, 480}, {300, 60}, 40, 2.06, 6.75);
  // WHEN fitted
  const BodyFit f = fit_body(d.img, d.face, kPreset, BodyFitParams{});
  std::printf("as preset: separation %.2f width %.3f height %.3f shift %.3f\n", f.separation, f.width_ratio, f.height_ratio, f.shift);
  // THEN accepted, measured within the tolerance, and the box is the preset's
  EXPECT_EQ(f.refused, FaceRefusal::kNone);
  EXPECT_GT(f.separation, 0.9);
  EXPECT_NEAR(f.width_ratio, 1.0, 0.05);
  EXPECT_NEAR(f.height_ratio, 1.0, 0.05);
  EXPECT_EQ(f.box, body_from_face(d.face, kPreset));
}

TEST(BodyFit, NarrowShortPersonGetsANarrowerShorterBox) {
  // GIVEN a person 1.5 face widths wide whose feet are 5 face heights below the face top (the preset: 2.06, 6.75)
  const Drawn d = draw_person({640, 480}, {300, 60}, 40, 1.5, 5.0, 3.0);
  const BodyFit f = fit_body(d.img, d.face, kPreset, BodyFitParams{});
  std::printf("narrow, short: width %.3f height %.3f -> box %.1f x %.1f\n", f.width_ratio, f.height_ratio, f.box.width, f.box.height);
  // THEN the box is the person's: 80 px wide (1.5 x 40 / 0.75), from 10 px above the face top to the feet (5.25 x 40)
  ASSERT_EQ(f.refused, FaceRefusal::kNone);
  EXPECT_NEAR(f.box.width, 80.0, 3.0);
  EXPECT_NEAR(f.box.height, 210.0, 3.0);
  EXPECT_NEAR(f.box.x + f.box.width / 2, 320.0, 1.0);  // still centred on the face
  EXPECT_NEAR(f.box.y, 50.0, 1e-9);
  EXPECT_NEAR(f.body.width_in_faces, 2.0, 0.08);
}

TEST(BodyFit, WidePersonGetsAWiderBoxWithinTheBound) {
  const BodyFitParams p;
  // GIVEN a person 2.6 face widths wide (1.26 of the preset's 2.06), and one 2.9 wide (1.41: beyond fit_max 1.3)
  const Drawn wide = draw_person({640, 480}, {300, 60}, 40, 2.6, 6.75);
  const BodyFit f = fit_body(wide.img, wide.face, kPreset, p);
  const Drawn wider = draw_person({640, 480}, {300, 60}, 40, 2.9, 6.75);
  const BodyFit g = fit_body(wider.img, wider.face, kPreset, p);
  std::printf("wide: separation %.2f width %.3f -> %.1f px; wider: separation %.2f width %.3f -> %.1f px\n", f.separation,
              f.width_ratio, f.box.width, g.separation, g.width_ratio, g.box.width);
  ASSERT_EQ(f.refused, FaceRefusal::kNone);
  ASSERT_EQ(g.refused, FaceRefusal::kNone);
  // THEN 139 px (2.6 x 40 / 0.75) for the first; the second is held at fit_max of the preset (1.3 x 110 px);
  // heights unchanged
  EXPECT_NEAR(f.box.width, 138.7, 3.0);
  EXPECT_NEAR(g.box.width, p.fit_max * 110.0, 1e-6);
  EXPECT_NEAR(f.box.height, 280.0, 1e-6);
  EXPECT_NEAR(g.box.height, 280.0, 1e-6);
}

TEST(BodyFit, BodyBesideTheFaceMovesTheBoxWithinTheBound) {
  const BodyFitParams p;
  // GIVEN a person leaning: the body (2.5 face widths wide) centred 0.7 face widths right of the face (28 px
  // for a 40 px face)
  const Drawn d = draw_person({640, 480}, {300, 60}, 40, 2.5, 6.75, 3.5, 0.7);
  const BodyFit f = fit_body(d.img, d.face, kPreset, p);
  std::printf("beside: separation %.2f shift %.2f face widths, width %.3f (%d)\n", f.separation, f.shift, f.width_ratio, f.width_seen);
  ASSERT_EQ(f.refused, FaceRefusal::kNone);
  // THEN the box moves right by max_shift_in_faces (0.5 x 40 = 20 px) and is the body's width (133 px)
  EXPECT_NEAR(f.shift, 0.7, 0.05);
  EXPECT_NEAR(f.box.x + f.box.width / 2, 320.0 + p.max_shift_in_faces * 40, 1e-6);
  EXPECT_NEAR(f.box.width, 133.3, 3.0);
  // AND a body within the tolerance of the face's centre (0.3 face widths: under 0.2 of the box's width) leaves it
  const Drawn near = draw_person({640, 480}, {300, 60}, 40, 2.06, 6.75, 3.5, 0.3);
  EXPECT_EQ(fit_body(near.img, near.face, kPreset, p).box, body_from_face(near.face, kPreset));
}

// face_from_body: where a box puts the face, for the re-check's torso test; body_from_face's inverse, also for a
// box fitted off the face's centre.
TEST(BodyProportions, FaceFromBodyInvertsBodyFromFace) {
  BodyProportions fitted = kPreset;
  fitted.width_in_faces = 2.2;
  fitted.centre_in_faces = -0.3;
  for (const BodyProportions& p : {kPreset, fitted}) {
    const cv::Rect2d face(301.5, 62.25, 40, 44);
    const cv::Rect2d back = face_from_body(body_from_face(face, p), p);
    EXPECT_NEAR(back.x, face.x, 1e-9);
    EXPECT_NEAR(back.y, face.y, 1e-9);
    EXPECT_NEAR(back.width, face.width, 1e-9);
    EXPECT_NEAR(back.height, face.height, 1e-9);
  }
}

// carried_with_box: a face given with one box, where a moved and scaled box puts it (the re-check's face on the
// next frame, the hands stage's last face); the face a box makes is carried to the face the other box makes.
TEST(BodyProportions, CarriedWithBoxKeepsThePlaceInUnitsOfTheBox) {
  const cv::Rect2d from(100, 50, 80, 200), to(130, 40, 120, 300);  // moved, and 1.5 times larger
  const cv::Rect2d c = carried_with_box(cv::Rect2d(120, 60, 30, 30), from, to);
  EXPECT_DOUBLE_EQ(c.x, 160.0);  // 20 px into the box: 30 px into the larger one
  EXPECT_DOUBLE_EQ(c.y, 55.0);
  EXPECT_DOUBLE_EQ(c.width, 45.0);
  EXPECT_DOUBLE_EQ(c.height, 45.0);
  const cv::Rect2d made = carried_with_box(face_from_body(from, kPreset), from, to), want = face_from_body(to, kPreset);
  EXPECT_NEAR(made.x, want.x, 1e-9);
  EXPECT_NEAR(made.y, want.y, 1e-9);
  EXPECT_NEAR(made.width, want.width, 1e-9);
  EXPECT_NEAR(made.height, want.height, 1e-9);
  // A box without area carries nothing: the rectangle as given.
  EXPECT_EQ(carried_with_box(cv::Rect2d(1, 2, 3, 4), cv::Rect2d(0, 0, 0, 10), to), cv::Rect2d(1, 2, 3, 4));
}

TEST(BodyFit, FaceNearTheBottomEdgeIsRefused) {
  // GIVEN a face whose chin is 10 px above the frame's bottom (the body below the image)
  const Drawn d = draw_person({640, 480}, {300, 430}, 40, 2.75, 7.0);
  const BodyFit f = fit_body(d.img, d.face, kPreset, BodyFitParams{});
  // THEN refused: 1.5 of the box's 7 face heights are in the frame (from 0.25 above the face top)
  EXPECT_EQ(f.refused, FaceRefusal::kOffFrame);
  EXPECT_NEAR(f.in_frame, 1.5 / 7.0, 1e-9);
  // AND with the frame check off, the torso sample under the chin is out of view
  BodyFitParams no_frame_check;
  no_frame_check.min_in_frame = 0;
  EXPECT_EQ(fit_body(d.img, d.face, kPreset, no_frame_check).refused, FaceRefusal::kNoTorso);
}

TEST(BodyFit, FeetInsideTheFrameShrinkABoxThatRanOffTheBottom) {
  // GIVEN the dancing person of the issue: the preset box runs off the bottom (face top at 200, preset bottom
  // 200 - 20 + 560 = 740 > 480) but the feet are at 200 + 3.5 x 80 = 480 - 0 ... here at 440
  const Drawn d = draw_person({640, 480}, {280, 200}, 80, 2.75, 3.0, 2.0);
  const BodyFit f = fit_body(d.img, d.face, kPreset, BodyFitParams{});
  std::printf("ran off: in frame %.2f, height %.3f seen %d -> box bottom %.1f\n", f.in_frame, f.height_ratio, f.height_seen, f.box.br().y);
  ASSERT_EQ(f.refused, FaceRefusal::kNone);
  // THEN the box ends at the feet, 200 + 3 x 80 = 440, within the frame, though held at fit_min of the preset
  // (0.6 x 560 = 336: bottom 180 + 336 = 516)
  EXPECT_TRUE(f.height_seen);
  EXPECT_NEAR(f.box.height, BodyFitParams{}.fit_min * 560.0, 1e-6);
  EXPECT_LT(f.box.br().y, body_from_face(d.face, kPreset).br().y);
}

TEST(BodyFit, FaceOnAPosterOrAShirtIsRefused) {
  // GIVEN a face on a uniform poster (the same colour below it as beside it)
  cv::Mat img = test::texture({640, 480}, 3);
  cv::rectangle(img, cv::Rect(150, 40, 340, 440), cv::Scalar(200, 200, 230), cv::FILLED);
  cv::ellipse(img, cv::Point(320, 120), cv::Size(20, 20), 0, 0, 360, kSkin, cv::FILLED);
  const BodyFit poster = fit_body(img, cv::Rect2d(300, 100, 40, 40), kPreset, BodyFitParams{});
  // AND a small face printed on a wide shirt (the shirt 6 face widths wide from the face up to beyond the frame)
  const Drawn shirt = draw_person({640, 480}, {310, 200}, 20, 12.0, 20.0, 20.0);
  const BodyFit printed = fit_body(shirt.img, shirt.face, kPreset, BodyFitParams{});
  std::printf("poster separation %.3f, shirt print %.3f\n", poster.separation, printed.separation);
  // THEN both are refused: no body under the face
  EXPECT_EQ(poster.refused, FaceRefusal::kNoBodyColour);
  EXPECT_EQ(printed.refused, FaceRefusal::kNoBodyColour);
  // AND with the evidence check off they are not
  BodyFitParams off;
  off.min_separation = 0;
  EXPECT_EQ(fit_body(img, cv::Rect2d(300, 100, 40, 40), kPreset, off).refused, FaceRefusal::kNone);
}

TEST(BodyFit, ThePhotographsPeopleAreAccepted) {
  TrackerParams tp;
  FaceDetector faces(tp, load_face_cascade(tp));
  for (const char* name : {"messi5.jpg", "astronaut.png"}) {
    const cv::Mat img = photo(name);
    ASSERT_FALSE(img.empty()) << name;
    const auto face = faces.detect(img);
    ASSERT_TRUE(face.has_value()) << name;
    const BodyFit f = fit_body(img, face->face, tp.body(), tp.body_fit);
    std::printf("%s: face %.0f,%.0f %.0fx%.0f in frame %.2f separation %.3f width %.3f (%d) height %.3f (%d) shift %.2f -> %.0f,%.0f %.0fx%.0f\n",
                name, face->face.x, face->face.y, face->face.width, face->face.height, f.in_frame, f.separation,
                f.width_ratio, f.width_seen, f.height_ratio, f.height_seen, f.shift, f.box.x, f.box.y, f.box.width, f.box.height);
    EXPECT_EQ(f.refused, FaceRefusal::kNone) << name << ": " << refusal_text(f.refused);
    // and both keep the preset box: Messi's silhouette is within the tolerance (1.13 wide, 0.89 tall), the
    // astronaut's white suit separates too little from the sky and flag beside her to fit to (0.27).
    EXPECT_EQ(f.box, body_from_face(face->face, tp.body())) << name;
  }
}

// The astronaut photograph shrunk to `size` px; her face (cascade) is at about (124, 46) 68x68 at 360 px.
cv::Mat astronaut(int size) {
  cv::Mat out;
  cv::resize(photo("astronaut.png"), out, cv::Size(size, size), 0, 0, cv::INTER_AREA);
  return out;
}

// Frames until a track starts (at most `max_frames`), counting the frames that refused a face.
struct Searched {
  TrackOutput out;
  int frames = 0;
  int refused_frames = 0;
};
Searched search(UserTracker& t, const cv::Mat& frame, int max_frames) {
  Searched s;
  while (s.frames < max_frames) {
    s.out = t.process(frame);
    ++s.frames;
    if (s.out.refused != FaceRefusal::kNone) ++s.refused_frames;
    if (s.out.status == TrackStatus::kTracking) break;
  }
  return s;
}

TEST(UserTrackerBodyCheck, FaceAtTheBottomEdgeStartsNoTrack) {
  // GIVEN the top 120 rows of the astronaut (360 px) at the bottom of a grey 640x360 frame: her face whole,
  // 6 px above the bottom edge, her body below the image
  cv::Mat frame(360, 640, CV_8UC3, cv::Scalar(90, 90, 90));
  astronaut(360)(cv::Rect(0, 0, 360, 120)).copyTo(frame(cv::Rect(140, 240, 360, 120)));
  const TrackerParams p;
  const int scan = FaceDetector(p, load_face_cascade(p)).scan_tiles(frame.size());
  // WHEN the tracker searches for two whole scans of the frame
  UserTracker t(p, load_tracker_models(p));
  const Searched s = search(t, frame, 2 * scan);
  // THEN no track: her face is found and refused (counted) on each scan, and the search goes on
  EXPECT_EQ(s.out.status, TrackStatus::kSearching);
  EXPECT_EQ(s.frames, 2 * scan);
  EXPECT_GE(s.refused_frames, 2);
  EXPECT_EQ(t.refusals(FaceRefusal::kOffFrame), s.refused_frames);
  EXPECT_FALSE(s.out.face.has_value());
  // AND with the frame checks off, the same face starts a track (the refusal was the check's)
  TrackerParams off = p;
  off.body_fit.min_in_frame = 0;
  off.body_fit.min_torso_in_frame = 0;
  UserTracker u(off, load_tracker_models(off));
  EXPECT_EQ(search(u, frame, scan).out.status, TrackStatus::kTracking);
}

// A poster (a flat pale board) with the astronaut's face printed on it (80 px), at the left of a 960x540
// frame, and the astronaut herself (a 300 px photograph: face about 57 px) at the right.
cv::Mat poster_and_astronaut() {
  cv::Mat frame = test::texture({960, 540}, 11);
  frame(cv::Rect(0, 20, 560, 500)).setTo(cv::Scalar(215, 225, 230));
  const cv::Mat big = astronaut(422);  // face about 80 px at (146, 54)
  big(cv::Rect(138, 46, 96, 96)).copyTo(frame(cv::Rect(232, 72, 96, 96)));
  astronaut(300).copyTo(frame(cv::Rect(620, 120, 300, 300)));
  return frame;
}

TEST(UserTrackerBodyCheck, FaceOnAPosterIsRefusedAndTheScanGoesOnToThePerson) {
  // GIVEN the poster and the astronaut
  const cv::Mat frame = poster_and_astronaut();
  const TrackerParams p;
  const int scan = FaceDetector(p, load_face_cascade(p)).scan_tiles(frame.size());
  // WHEN the tracker searches
  UserTracker t(p, load_tracker_models(p));
  const Searched s = search(t, frame, 2 * scan);
  std::printf("poster: %d frames, %d refused (%lld no body colour, %lld off the frame, %lld no torso)\n", s.frames,
              s.refused_frames, static_cast<long long>(t.refusals(FaceRefusal::kNoBodyColour)),
              static_cast<long long>(t.refusals(FaceRefusal::kOffFrame)), static_cast<long long>(t.refusals(FaceRefusal::kNoTorso)));
  // THEN the printed face is refused (its torso sample is the board beside it) and the scan goes on past it
  // to the astronaut: the track starts on her within one scan of the frame
  EXPECT_GE(t.refusals(FaceRefusal::kNoBodyColour), 1);
  ASSERT_EQ(s.out.status, TrackStatus::kTracking);
  EXPECT_LE(s.frames, scan);
  ASSERT_TRUE(s.out.face.has_value());
  EXPECT_GT(s.out.face->x, 620.0) << *s.out.face;
  // AND without the evidence check the printed face (the larger, found first) starts the track
  TrackerParams off = p;
  off.body_fit.min_separation = 0;
  UserTracker u(off, load_tracker_models(off));
  const Searched o = search(u, frame, scan);
  ASSERT_EQ(o.out.status, TrackStatus::kTracking);
  ASSERT_TRUE(o.out.face.has_value());
  EXPECT_LT(o.out.face->x, 560.0) << *o.out.face;
}

// The same frame searched whole at once (face.scan_slice_pixels 0): both faces come from one search, the
// printed one first (the larger); it is refused and the next face is tried on the same frame.
TEST(UserTrackerBodyCheck, TheNextFaceOfTheSameSearchIsTriedAfterARefusal) {
  TrackerParams p;
  p.face.scan_slice_pixels = 0;
  const cv::Mat frame = poster_and_astronaut();
  UserTracker t(p, load_tracker_models(p));
  const TrackOutput out = t.process(frame);
  ASSERT_EQ(out.status, TrackStatus::kTracking);
  EXPECT_EQ(out.refused, FaceRefusal::kNoBodyColour);  // the printed face, refused on this frame
  EXPECT_EQ(t.refusals(FaceRefusal::kNoBodyColour), 1);
  ASSERT_TRUE(out.face.has_value());
  EXPECT_GT(out.face->x, 620.0) << *out.face;
  // The search's order: the printed face (larger) first.
  const auto faces = FaceDetector(p, load_face_cascade(p)).detect_all(frame);
  ASSERT_GE(faces.size(), 2u);
  EXPECT_LT(faces[0].face.x, 560.0);
  EXPECT_GE(faces[0].face.area(), faces[1].face.area());
}

}  // namespace
}  // namespace gpilot
