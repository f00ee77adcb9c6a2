// Parameters of gpilot-tracker (section `tracker`): Haar face search, body box, DSST (Danelljan et al.,
// BMVC 2014, the published settings as defaults) and loss detection.
#pragma once

#include <string>

#include "body_proportions.hpp"
#include "config_schema.hpp"

namespace gpilot {

struct FaceDetectorParams {
  std::string cascade = "/usr/share/opencv4/haarcascades/haarcascade_frontalface_alt2.xml";  //!< from opencv-data
  double scale_factor = 1.1;  //!< detectMultiScale pyramid step
  int min_neighbors = 5;      //!< detectMultiScale: 5 gives no false positive on messi5.jpg, 3 does
  int min_face_px = 20;       //!< smallest face searched for, pixels (in the searched image)
  double downscale = 1.0;     //!< search a copy shrunk by this factor (1 = full size)
  // The per-frame budget of a face search: the cascade's cost grows with the pixels searched (a 1280x720 frame
  // took ~100 ms here, 10 fps while searching). A larger image is searched on a copy shrunk to this many
  // pixels (a face must then be min_face_px in the shrunk copy).
  double max_search_pixels = 640.0 * 480.0;
  // The whole-frame search while SEARCHING or LOST is spread over frames (FaceDetector::scan_step): octaves of
  // face sizes, each cut into overlapping tiles, at most scan_slice_pixels searched per frame (at least one
  // tile), the large faces first. 0: the whole frame in one go every time.
  double scan_slice_pixels = 60000.0;
  // The paper's range (issue 13): the cascade's smallest face is its 20 px window, so a face below min_face_px
  // is found only in an enlarged copy. With upscale > 1 the whole-frame scan ends with one more octave, the
  // frame enlarged by this factor (faces min_face_px / upscale .. min_face_px in the frame), and a search of a
  // small window (re-check, local search: enlarged, at most max_search_pixels) looks there for them too.
  // The synthetic user's face (Haar box 20.8 px at 5 m) is found by one whole scan to 4.5 m at 1, at every
  // half metre from 5 to 8 m at 2 (not at 8.5 m, again at 9 to 10 m: the cascade's window steps); the extra
  // octave makes a 640x480 scan 49 tiles instead of 13 (2 s at 25 fps instead of 0.5 s).
  double upscale = 2.0;
  // The face re-check (a small window around where the box puts the face) expecting a face below
  // recheck_small_face_px searches its window enlarged so that the face is recheck_enlarged_face_px: a face
  // just above the cascade's 20 px window in the upscale copy is found on a third of the frames. The far
  // scenario's frames at 5..10 m (re-check windows on the true face, 210 frames): upscale 2 found the face on
  // 122 (10-12 px faces: 50 of 133), enlarged to 40 px on 209, to 50 px on all. 0: off.
  double recheck_small_face_px = 24.0;
  double recheck_enlarged_face_px = 48.0;
  // The re-check's pyramid step, finer than the search's: the face's box comes in scale_factor steps, so at 1.1
  // a user standing still was found 87.9 .. 100.8 px of box width from one re-check to the next, each one a
  // resize past face_recheck_tolerance (open loop `idle` started on its truth: AUC 0.922 against DSST alone's
  // 0.950; at 1.03, 0.948). Its window is a few faces wide, so the finer step costs little.
  double recheck_scale_factor = 1.03;

  template <class V>
  void visit(V& v) {
    v("cascade", cascade, "Haar cascade file (opencv-data)");
    v("scale_factor", scale_factor, 1.01, 2.0, "detectMultiScale scale step");
    v("min_neighbors", min_neighbors, 0, 50, "detectMultiScale minNeighbors");
    v("min_face_px", min_face_px, 8, 1000, "smallest face searched, pixels");
    v("downscale", downscale, 1.0, 8.0, "search on a copy shrunk by this factor");
    v("max_search_pixels", max_search_pixels, 1e4, 1e8, "a face search shrinks its image to at most this many pixels");
    v("scan_slice_pixels", scan_slice_pixels, 0.0, 1e8, "whole-frame search: pixels searched per frame, spread over frames (0: all at once)");
    v("upscale", upscale, 1.0, 4.0, "faces below min_face_px are searched in a copy enlarged by this (1: off)");
    v("recheck_small_face_px", recheck_small_face_px, 0.0, 1000.0, "re-check: an expected face below this is searched enlarged (0: off)");
    v("recheck_enlarged_face_px", recheck_enlarged_face_px, 20.0, 1000.0, "re-check: ... in its window enlarged to make the face this size");
    v("recheck_scale_factor", recheck_scale_factor, 1.01, 2.0, "re-check: detectMultiScale scale step (finer than the search's: steadier face sizes)");
  }
};

struct DsstParams {
  double lambda = 0.01;               //!< regularisation λ of H = conj(G)F / (ΣF conj(F) + λ)
  double learning_rate = 0.025;       //!< η, update rate of numerator A and denominator B
  double padding = 1.0;               //!< search area = (1 + padding) × target size
  double output_sigma_factor = 1.0 / 16.0;  //!< translation Gaussian σ = factor × target size
  int cell_size = 4;                  //!< FHOG cell, pixels
  int number_of_scales = 33;          //!< S, scale filter length
  double scale_step = 1.02;           //!< a, ratio between neighbouring scales
  // Scale Gaussian σ = factor × number_of_scales / sqrt(33) (DSST code), in steps of scale_step: 0.25 is the
  // DSST code's 1.44 steps (one sampled scale of the BMVC filter); 0.3 is 1.72 steps, about one sampled scale of
  // scale_samples 19 (1.74 steps apart), as fDSST's 33/16 steps at 33/17 (1.06 samples).
  double scale_sigma_factor = 0.3;
  // fDSST's scale search (Danelljan et al., TPAMI 2017): only scale_samples scales are sampled (spread over
  // the same range as number_of_scales, each a FHOG extraction and a warp: the scale filter was about half the
  // tracker's time), and the response is interpolated to number_of_scales in the Fourier domain (zero-padded
  // spectrum). 0 (or >= number_of_scales): every scale sampled, the BMVC filter (with scale_sigma_factor 0.25).
  // fDSST's 17 lost 0.013 AUC on uav123_group1_1 (mean of 5 runs at η 0.023..0.027); 19 is within 0.01 of the
  // BMVC filter on every real clip at 25-35 % less time a frame (tracker README).
  int scale_samples = 19;
  // Speed bounds (not in the paper; fDSST and KCF do the same): the target is modelled at a resolution where
  // its area is at most max_model_area pixels (so the padded search window is at most 4× that, ~25x25 FHOG
  // cells), and a small target is enlarged to at least min_model_area so that it still spans a few cells.
  double max_model_area = 2500.0;     //!< target area at the model's resolution, pixels (upper bound)
  double min_model_area = 1200.0;     //!< target area at the model's resolution, pixels (lower bound)
  double scale_model_max_area = 512.0;  //!< scale samples are resized to at most this area (DSST code: 512)
  int psr_exclude_cells = 2;          //!< PSR sidelobe excludes a (2k+1)^2-cell square around the peak
  // The DSST code samples the frame again at the new estimate to learn; learning from the samples the
  // estimate was found in, with the labels centred on the estimate, halves the cost (see the eval note).
  bool reuse_detection_samples = true;
  // Staple (Bertinetto et al., CVPR 2016): a per-pixel colour-histogram score (foreground against the
  // surrounding window) averaged over a target-sized box, merged with the correlation response as
  // (1 - colour_weight) * filter + colour_weight * colour. 0: off (the filter alone). PSR stays the filter's.
  // Staple's 0.3 lost person12_1 (0.479 -> 0.271: the colour pulled the box onto a like-coloured neighbour);
  // 0.15 gains on 5 of 6 real clips and the synthetic tour (tracker README).
  double colour_weight = 0.15;
  double colour_learning_rate = 0.04;  //!< Staple's 0.04
  // The colour score of a cell: P(target | colour) weighted by a Gaussian of this fraction of the target's
  // sides centred there (0: Staple's mean over a target-sized box). Where the target is smaller than its box
  // (dtb70_Surfing06's surfer crouching, 39x67 -> 18x30 px, while the box keeps about 34x49) the box's mean
  // is flat over every position that holds the target, so it could not pull the box back onto it, and the
  // filter slid onto the spray below; the Gaussian peaks on the target's colours (tracker README).
  double colour_centre_sigma = 0.1;
  // Each side of the search window is at least min_window_side x (1 + padding) x sqrt(target area) (0: off, the
  // paper's (1 + padding) x each side). A narrow target's window was 2 of its widths wide: uav123_group3_2's
  // 15x64 px person, panning 18-26 px a frame, left it at frame 74; CSRT's window is square-ish. At 0.8 a
  // target taller than 1.56x its width gets a wider window (group3_2: 3.3 widths), others keep the paper's.
  // It needs the Gaussian colour score: with Staple's box the wider window lost dtb70_Surfing06 to the waves.
  double min_window_side = 0.8;
  // A frame whose response is weak (PSR below wide_search_psr) is searched again in the 8 windows around, each
  // wide_search_offset of a window's side away; the best is taken if its PSR reaches wide_search_accept_psr
  // (a sure frame: redetect_psr's 10; from 7 it jumped onto the waves of dtb70_Surfing06, -0.14 AUC). A fast
  // pan (uav123_person12_1: 27 px a frame, two thirds of the target's width) had left the window: 0.48 -> 0.77.
  // Not while LOST (the re-detection searches one window). 0: off.
  double wide_search_psr = 7.0;
  double wide_search_offset = 0.5;
  double wide_search_accept_psr = 10.0;
  // ... and at least this share of the track's mean PSR over its good frames: a still cut to another scene gave
  // windows at PSR 10+ where the track had run at 36..60 (UserTracker.CutToAnotherScene...).
  double wide_search_accept_share = 0.5;

  template <class V>
  void visit(V& v) {
    v("lambda", lambda, 1e-6, 10.0, "filter regularisation lambda (paper 0.01)");
    v("learning_rate", learning_rate, 0.0, 1.0, "model learning rate eta (paper 0.025)");
    v("padding", padding, 0.0, 4.0, "search area = (1 + padding) x target (paper 1)");
    v("output_sigma_factor", output_sigma_factor, 1e-3, 1.0, "translation Gaussian sigma / target size (paper 1/16)");
    v("cell_size", cell_size, 1, 16, "FHOG cell size, pixels (paper 4)");
    v("number_of_scales", number_of_scales, 1, 129, "scales in the scale filter (paper 33)");
    v("scale_step", scale_step, 1.001, 1.5, "ratio between neighbouring scales (paper 1.02)");
    v("scale_sigma_factor", scale_sigma_factor, 1e-3, 4.0, "scale Gaussian sigma = factor x scales / sqrt(33) (paper 1/4)");
    v("scale_samples", scale_samples, 0, 129, "fDSST: scales sampled, response interpolated to number_of_scales (0: all sampled, the BMVC filter; fDSST 17)");
    v("max_model_area", max_model_area, 100.0, 1e6, "target area at model resolution, upper bound, pixels");
    v("min_model_area", min_model_area, 16.0, 1e6, "target area at model resolution, lower bound, pixels");
    v("scale_model_max_area", scale_model_max_area, 16.0, 1e5, "scale sample area bound, pixels (DSST 512)");
    v("psr_exclude_cells", psr_exclude_cells, 0, 20, "PSR: half-width of the peak square left out, cells");
    v("reuse_detection_samples", reuse_detection_samples, "learn from the detection samples (false: sample again, as DSST)");
    v("colour_weight", colour_weight, 0.0, 1.0, "Staple: weight of the colour-histogram response (0: off; Staple 0.3)");
    v("colour_learning_rate", colour_learning_rate, 0.0, 1.0, "Staple: colour histograms' update rate (Staple 0.04)");
    v("min_window_side", min_window_side, 0.0, 4.0, "window sides at least this x (1 + padding) x sqrt(target area) (0: the paper's (1 + padding) x each side)");
    v("colour_centre_sigma", colour_centre_sigma, 0.0, 4.0, "colour score: Gaussian weight of this fraction of the target's sides (0: Staple's target-sized box)");
    v("wide_search_psr", wide_search_psr, 0.0, 100.0, "PSR below this: the 8 windows around are searched too (0: off)");
    v("wide_search_offset", wide_search_offset, 0.05, 2.0, "wide search: the windows' offset, fraction of the window's side");
    v("wide_search_accept_psr", wide_search_accept_psr, 0.0, 100.0, "wide search: a window is taken at this PSR at least");
    v("wide_search_accept_share", wide_search_accept_share, 0.0, 10.0, "wide search: ... and at this share of the track's mean PSR of its good frames");
  }
};

// Before a track starts on a face (SEARCHING, or a LOST track re-anchored on one), the body box the head-body
// ratios give is checked against the image (body_fit.hpp): on held-out videos a dancing person's face box gave
// a body box much larger than the person, running off the bottom of the frame. All lengths in face widths
// (horizontal) or face heights (vertical) of the cascade's face box.
struct BodyFitParams {
  // A face whose preset body box lies mostly outside the frame (a face at the bottom edge, the body below it)
  // is refused: too little of the person to learn a filter from. 0: off.
  double min_in_frame = 0.5;           //!< fraction of the preset box's area that must be inside the frame
  // The torso sample: below the chin (the neck left out), centred on the face.
  double torso_gap_in_faces = 0.25;    //!< torso sample's top below the face box's bottom, face heights
  double torso_height_in_faces = 1.5;  //!< torso sample height, face heights
  double torso_half_width_in_faces = 0.5;  //!< torso sample half width, face widths
  double min_torso_in_frame = 0.5;     //!< fraction of the torso sample inside the frame, else no evidence
  // The background beside the person: two strips just outside the largest box the fit may give (fit_max of
  // the preset), level with the torso sample (the evidence) or from the chin to the box's bottom (the fit).
  double beside_width_in_faces = 1.0;  //!< each strip's width, face widths
  // Colour evidence of a body under the face: 1 - Bhattacharyya coefficient of the torso sample's and the
  // strips' colour histograms (0: the same colours, 1: none shared). A face printed on a poster or a T-shirt
  // has the same poster or shirt below it as beside it (0.00 in the tests). Real people: 0.21..0.82 over the
  // 13 faces the cascade finds among ../shared/data/real_people's 62 COCO persons, so not higher. 0: off.
  double min_separation = 0.1;
  int bins_per_channel = 8;            //!< colour histogram bins per BGR channel (grey frames: this many levels)
  double fit_face_px = 24.0;           //!< the evidence is read in a copy where the face is at most this wide
  // The fit: the person's extent from the colour evidence (P(person | colour) from the centre band against
  // the strips beside the box): width where the chest band's columns are the person's, bottom where the
  // centre band's rows stop being. Applied only when it differs from the preset by more than fit_tolerance,
  // clamped to [fit_min, fit_max] of the preset (both 1: no fit); the box stays centred on the face within
  // max_shift_in_faces. The track keeps the fitted ratios (the face re-check re-anchors with them).
  // real_people: fitting from 0.3 (7 widths fitted) gave a mean IoU with COCO's person box of 0.589, from 0.5
  // 0.615 (preset 0.606).
  double fit_min_separation = 0.5;     //!< weaker colour evidence (still a body) keeps the preset box
  double fit_min = 0.6;                //!< smallest fitted width or height, fraction of the preset
  double fit_max = 1.3;                //!< largest fitted width or height, fraction of the preset
  // The head-body ratio's box ends at the thighs, not the feet: a standing person's legs always go on below
  // it. Fitted to the feet whenever they are in view (the user 5 m or more from the drone: 1.3x the preset at
  // the bound), the box moved the body centre down the legs, and a hand in front of the belly (FURTHER) read
  // as above it (CLOSER: the drone flew in from 5 to 2.5 m in the `far` scenario). So the height is only
  // shrunk (a box that runs far below the person, the dancer of issue 13), never grown. 1.3: the old fit.
  double fit_max_height = 1.0;         //!< largest fitted height, fraction of the preset
  // The synthetic person's chest silhouette over every scenario is 0.87..1.11 of the preset's: 0.15 left
  // the box of some frames of `nuisances` 13 % narrower than the box the hands rules were tuned on.
  double fit_tolerance = 0.2;          //!< a fitted side within this fraction of the preset keeps the preset
  double skin_sample_in_faces = 0.5;   //!< the face box's middle (this fraction of its sides) is the person's colours too
  // The preset box is wider than the person's silhouette at the chest (arms at the sides): a margin for the
  // arms to move. The synthetic person's silhouette is 0.65..0.83 of the preset width over the scenarios (the
  // box the hands rules were tuned on), Messi's (messi5.jpg) 0.85.
  double silhouette_width_in_box = 0.75;  //!< the chest silhouette's width that gives the preset width, fraction of it
  double fit_person_p = 0.5;           //!< a pixel is the person's when P(person | colour) is at least this
  double fit_column_fraction = 0.5;    //!< a chest column is the person's when this fraction of it is
  double fit_row_fraction = 0.3;       //!< a centre-band row is the person's when this fraction of it is (legs apart)
  double fit_gap_in_faces = 0.5;       //!< rows not the person's over at most this (a belt, a hand) do not end it, face heights
  double max_shift_in_faces = 0.5;     //!< the fitted box's centre at most this far from the face's, face widths

  template <class V>
  void visit(V& v) {
    v("min_in_frame", min_in_frame, 0.0, 1.0, "refuse a face whose body box has less of its area in the frame (0: off)");
    v("torso_gap_in_faces", torso_gap_in_faces, 0.0, 5.0, "torso sample's top below the face bottom, face heights");
    v("torso_height_in_faces", torso_height_in_faces, 0.1, 10.0, "torso sample height, face heights");
    v("torso_half_width_in_faces", torso_half_width_in_faces, 0.1, 5.0, "torso sample half width, face widths");
    v("min_torso_in_frame", min_torso_in_frame, 0.0, 1.0, "refuse a face with less of its torso sample in the frame");
    v("beside_width_in_faces", beside_width_in_faces, 0.1, 10.0, "background strips beside the largest fitted body box, each this wide, face widths");
    v("min_separation", min_separation, 0.0, 1.0, "refuse a face whose torso colours separate less from the background beside (0: off)");
    v("bins_per_channel", bins_per_channel, 2, 32, "colour histogram bins per channel");
    v("fit_face_px", fit_face_px, 4.0, 1000.0, "body evidence read where the face is at most this wide, pixels");
    v("fit_min_separation", fit_min_separation, 0.0, 1.0, "fit the box only when the torso's colour separation is at least this");
    v("fit_min", fit_min, 0.1, 1.0, "fitted body width/height at least this fraction of the preset");
    v("fit_max", fit_max, 1.0, 10.0, "fitted body width/height at most this fraction of the preset");
    v("fit_max_height", fit_max_height, 0.1, 10.0, "fitted body height at most this fraction of the preset (1: only shrunk)");
    v("fit_tolerance", fit_tolerance, 0.0, 10.0, "fitted side within this fraction of the preset: keep the preset");
    v("skin_sample_in_faces", skin_sample_in_faces, 0.0, 1.0, "fit: the face's middle, this fraction of its sides, counts as the person's colours (bare arms)");
    v("silhouette_width_in_box", silhouette_width_in_box, 0.1, 2.0, "fit: chest silhouette width / body box width of the preset");
    v("fit_person_p", fit_person_p, 0.0, 1.0, "pixel is the person's when P(person | colour) is at least this");
    v("fit_column_fraction", fit_column_fraction, 0.0, 1.0, "chest column is the person's when this fraction of it is");
    v("fit_row_fraction", fit_row_fraction, 0.0, 1.0, "centre-band row is the person's when this fraction of it is");
    v("fit_gap_in_faces", fit_gap_in_faces, 0.0, 10.0, "a gap in the person's rows up to this does not end them, face heights");
    v("max_shift_in_faces", max_shift_in_faces, 0.0, 5.0, "fitted box centre at most this far from the face centre, face widths");
  }
};

// The person search (issue 30): BlazePose's person detector (services/pose, models/pose/pose_detection.onnx)
// finds the user without their face, to start a track and to take a lost user back. Off: the face search
// alone, as before. A run of the detector costs 20-40 ms (one core), so it runs on one searching frame in
// every_frames (the budget), each run on one region of the frame letterboxed to 224 px, and the search is
// spread over runs: while LOST the last box grown more with each run without the user; SEARCHING (and LOST
// once the grown box covers the frame), the whole frame, then tiles of tile_share of its short side in turn
// (a person 6 m or more from a 640x480 camera is too small in the whole frame for the detector: found to 5 m
// there, to 10 m in a 300 px region). HEALTH says how far it got.
struct PersonSearchParams {
  bool enabled = true;                     //!< tracker.person.enabled: the person detector searches too
  std::string models_dir = "models/pose";  //!< folder of pose_detection.onnx (relative: project root)
  double score_threshold = 0.5;            //!< detector score a person needs (MediaPipe 0.5)
  int every_frames = 5;                    //!< budget: the detector runs on one searching frame in this many
  double tile_share = 0.6;                 //!< the whole-frame search's tiles: squares of this x the frame's short side
  // While LOST the detector looks at the last box grown by region_growth x its height each side, and
  // region_growth_step more after each run that did not take the user back; a new user's confirming runs look
  // at their box grown by region_growth.
  double region_growth = 1.0;
  double region_growth_step = 1.0;
  // A new user (nobody remembered): the same person (body boxes overlapping by start_min_iou at least) found
  // by start_detections runs in a row, upright (the body's axis within max_tilt_deg of vertical), shoulders
  // and hips in the frame, and their body box checked against the image as a face's is (body_fit).
  int start_detections = 3;
  double start_min_iou = 0.3;
  double max_tilt_deg = 30.0;
  // The face the detection implies, for the head-body ratios, the torso sample and body_fit (the detector's own
  // face box does not follow the person's size): face_in_body x the distance from the hips to the full-body
  // scale point wide and high, its centre face_above_shoulders face widths above the shoulders' midpoint. The
  // synthetic user at 3-10 m: 0.165-0.235 (mean 0.20) and 0.85-1.13 (mean 1.0), test PersonSearch.*.
  double face_in_body = 0.2;
  double face_above_shoulders = 1.0;
  // Taking a remembered user back: the torso wears their clothes (recheck_min_torso_match), the face's width is
  // within max_size_change of their last (either way), and while LOST the track's last good filter, put on the
  // candidate, answers with a PSR of at least accept_psr (its box is then the new track's: the user's size and
  // shape carried on). Of several, the filter's best answer is taken. A bystander fails one of them.
  double max_size_change = 1.6;
  double accept_psr = 7.0;
  int max_candidates = 4;                  //!< detections scored a run at most (best detector scores first)

  template <class V>
  void visit(V& v) {
    v("enabled", enabled, "search for the user with BlazePose's person detector too (start without a face, re-acquisition)");
    v("models_dir", models_dir, "folder of pose_detection.onnx (relative: project root)");
    v("score_threshold", score_threshold, 0.0, 1.0, "person detector: score a person needs (MediaPipe 0.5)");
    v("every_frames", every_frames, 1, 1000, "budget: the detector runs on one searching frame in this many");
    v("tile_share", tile_share, 0.1, 1.0, "whole-frame search: after the frame itself, tiles of this x its short side in turn");
    v("region_growth", region_growth, 0.0, 100.0, "LOST: the detector's region, the last box grown by this x its height each side");
    v("region_growth_step", region_growth_step, 0.0, 100.0, "LOST: ... grown this much more after each run without the user");
    v("start_detections", start_detections, 1, 1000, "new user: detector runs in a row that find the same upright person in view");
    v("start_min_iou", start_min_iou, 0.0, 1.0, "new user: the same person between runs when their body boxes overlap this much (IoU)");
    v("max_tilt_deg", max_tilt_deg, 0.0, 180.0, "a person's body axis within this of vertical, degrees");
    v("face_in_body", face_in_body, 0.01, 2.0, "implied face width / the detection's hips-to-scale-point distance");
    v("face_above_shoulders", face_above_shoulders, -5.0, 5.0, "implied face centre above the shoulders' midpoint, face widths");
    v("max_size_change", max_size_change, 1.0, 10.0, "remembered user: face width within this factor of their last");
    v("accept_psr", accept_psr, 0.0, 1000.0, "LOST: the last good filter's PSR on a candidate needed to take it back");
    v("max_candidates", max_candidates, 1, 100, "detections scored per run at most");
  }
};

struct TrackerParams {
  FaceDetectorParams face;
  DsstParams dsst;
  BodyFitParams body_fit;
  PersonSearchParams person;
  // The paper's "preset head-body ratio" is not given. Ours: an adult is about 7.5 heads tall and a face
  // box from the cascade is about 0.8 of the head height; a box 2.75 face widths wide holds shoulders and
  // arms resting at the sides, 7 face heights tall reaches below the knees.
  double body_width_in_faces = 2.75;   //!< body box width / face box width
  double body_height_in_faces = 7.0;   //!< body box height / face box height
  double body_top_in_faces = 0.25;     //!< body box top sits this many face heights above the face box top
  BodyProportions body() const { return {body_width_in_faces, body_height_in_faces, body_top_in_faces, 0.0}; }
  // Bolme et al. (MOSSE, CVPR 2010): PSR is 20..60 while tracking and drops below 7 on failure. Measured
  // here: min 12.6 over OTB Crossing, 36 over cf_tracking_sample; 4..6 after a cut to another scene.
  double lost_psr = 7.0;               //!< PSR below this counts as a bad frame
  int lost_frames = 10;                //!< consecutive bad frames before LOST
  // A frame is learnt when its PSR is at least learn_psr: an occluder or a cut (PSR 4..6) is not absorbed
  // into the model. Not learning every frame below lost_psr lost small fast targets whose PSR dips to 6..7
  // while they turn (UAV123 wakeboard7: the model fell behind and jumped off at frame 20; DSST alone held on).
  double learn_psr = 6.0;
  // After LOST the last good model is not thrown away: on every frame it is run again (not learnt) from where
  // it last was; redetect_frames frames in a row with PSR >= redetect_psr re-find the target (a new track).
  // Not after a loss by face misses: there the model itself is what is in doubt (it slid onto the background).
  // After lost_search_frames frames LOST the last box is forgotten: SEARCHING (the face search only).
  double redetect_psr = 10.0;          //!< 0: no re-detection by the filter
  int redetect_frames = 2;
  int lost_search_frames = 50;         //!< frames LOST (last box kept, filter re-detection) before SEARCHING
  // While not tracking, the face search alternates, one search a frame: every search_full_stride-th frame the
  // whole (shrunk) frame, else, while LOST, the last good box grown by search_local_scale at full resolution,
  // within face.scan_slice_pixels too (a window over it, with its enlarged copy, is searched over frames).
  int search_full_stride = 2;          //!< 1: the whole frame every frame
  double search_local_scale = 2.0;     //!< local window = last body box grown by this factor (each side)
  // While LOST the whole-frame scan runs only for a user whose last face, grown by this, the scan could find
  // (its smallest face: face.min_face_px at the scan's resolution, over face.upscale; 17 px at 1280x720): a
  // drone's view of a far person (uav123_group3_2: a 5 px face) searched the whole frame for 2 s at 14.7 ms a
  // frame for nothing. The local search and the filter's re-detection go on; SEARCHING scans as ever. The local
  // search looks for faces up to the last one grown by this (a larger face is not the user's, the re-check's
  // gate; the scan, which runs for such a size, finds any): group3_2's went from 6 ms a frame (its 46x184 px
  // window and the enlarged copy, every face size) to about 1.5 (only the enlarged copy's 20-22 px windows).
  // 0: always, and any size.
  double lost_scan_face_growth = 2.0;
  // The bus adapter (gpilot-tracker): LCM queues 30 frames a channel by default, so a slow stage fell about a
  // second behind; at most camera_queue frames wait now, LCM drops those arriving while the queue is full, and
  // the stage counts the skipped ones (HEALTH.dropped).
  int camera_queue = 2;
  int opencv_threads = 0;              //!< cv::setNumThreads for the stage's process (0: no worker threads)
  // Not in the paper, which searches the face only to start: DSST's scale drifts by tens of percent while the
  // drone backs off or closes in, and every hand rule is a ratio of the box. Every this many tracked frames
  // the face is looked for where the box says it is (a small window, ~1 ms), and the box re-anchored on it
  // when they disagree by more than face_recheck_tolerance (scale or shift, fraction of the box width).
  int face_recheck_frames = 25;        //!< 0: never (the paper)
  double face_recheck_tolerance = 0.05;
  // ... and the face's width by more than this many pixels of the image the re-check searched (a far face's
  // window is enlarged: a fraction of a frame pixel) too: the cascade's boxes are whole pixels, and a user
  // standing still was found 35, 37, 36, 36 px wide at the re-check's finer pyramid step (dark-skin), a 2 px
  // swing that is 5.7 % of a 35 px face and resized the box for good (AUC 0.952 -> 0.860).
  double face_recheck_tolerance_px = 2.0;
  // A manual box (TRACKER_INIT) is re-anchored on the preset body box of the face its re-check finds: the flight
  // stage's speeds are in box widths and its view limits in box heights, so a box dragged by hand 20 % too wide
  // would fly 20 % slower. true: the box keeps the shape it was given, the track's ratios measured on the first
  // face found in it (an evaluation that scores the boxes against the annotation it started from:
  // gpilot-eval-tracker).
  bool manual_box_keeps_shape = false;
  // The re-check looks for faces from this share of the width the box expects: the cascade's smallest windows
  // cost most, and most on the face itself, where they pass deep into the cascade. At 0.5 a re-check at 3 m
  // (36 px face) took 11-18 ms, a frame -> USER_TRACK of 23-55 ms every second; a larger face than expected
  // is still taken up to twice the width (the scale gate).
  double face_recheck_min_share = 0.7;
  // A re-check changes the box's size by at most this share (up or down); the rest waits for the next re-check,
  // brought forward to weak_recheck_frames. A head turning away shows the cascade part of a face: in every
  // e2e turn-around run a re-check took one at 0.66-0.76 of the box's face and shrank the box to 0.69-0.84 of
  // the person for the 5 s the back was turned (IoU 0.49 in one: the track judged off the user); the drone
  // moving in or out gave re-check steps of 0.80-0.87 and 1.15-1.25 (e2e suite, 30 resizes).
  double face_recheck_max_step = 0.15;  //!< 0: no limit
  // A face the cascade cannot find is not by itself evidence of loss (a drone's view from above, a user far
  // away or turned away): a re-check miss counts only on a frame whose PSR is also weak (below
  // face_miss_psr). A track started from the face whose face has been missed so at this many re-checks in a
  // row, where the box puts it well inside the image, is LOST (the box slid onto the background). At the
  // image's edge a miss does not count (flight keeps the face in view: flight.keep_face_in_view).
  int face_recheck_misses = 3;         //!< 0: never LOST for this (manual tracks never are)
  double face_miss_psr = 12.0;         //!< a re-check miss counts only when the frame's PSR is below this
  // The user, not a bystander (issue 13): a face the re-check finds is the user's only when the torso under it
  // wears the user's clothes. A track started from a face keeps the chromaticity histogram of the torso under
  // it (body_fit's torso sample, torso_colour_bins^2 bins, pixels darker than torso_dark_level not read) and
  // blends in each re-check's that matches at torso_colour_rate; a face whose torso matches less than
  // recheck_min_torso_match (Bhattacharyya coefficient) is not the user's: no re-anchor, a miss; while LOST,
  // no track is started on it (once SEARCHING, any face may be the user). A passer-by with the user's face
  // (the same portrait) crossing between user and drone re-anchored the track on themselves at the re-check
  // and the drone followed them (scenario bystander). 0: off (manual tracks and grey frames have no torso
  // colours: never gated).
  double recheck_min_torso_match = 0.5;
  // And once SEARCHING: for user_memory_frames more, a face must still wear the lost user's clothes to start a
  // track; then any face may be the user (a user who changed clothes or light; gpilot-ctl's RESET forgets them
  // at once). A user who stepped out of view for over lost_search_frames handed the drone to whoever stood
  // in view (TrackerBystander.ALookAlikeIsNotTakenWhileTheUserIsAway).
  int user_memory_frames = 250;        //!< 0: any face once SEARCHING
  // A re-check that finds a face in other clothes where the box puts the face makes the track LOST (the box
  // is on someone else, or they stand in front of the user); on a frame whose PSR is below weak_recheck_psr such
  // a track is re-checked already after weak_recheck_frames: a look-alike walking in front took the filter with
  // them within 6 frames at PSR 8..9 (it still learns from 6), before the next second's re-check.
  int weak_recheck_frames = 3;
  double weak_recheck_psr = 12.0;
  // A torso that matches the clothes last found where the user's face should be (a re-check that found someone
  // else's face there, or neither face nor the user's clothes) better than the user's is not the user's: that
  // person again, over part of the user. Scenario bystander's look-alike walker crossing in front a second time:
  // a re-check found the user's face with the walker's shirt over the torso and restarted the filter there, on
  // the walker (they took the box 1-6 frames, the drone turning after it); or, the track LOST, the person search
  // took the walker back as the user (their torso, showing both shirts, matched the user's clothes 0.52, the gate
  // 0.5). A torso with more of the walker's shirt than the user's is then the walker's: LOST, refused.
  bool recheck_other_clothes = true;
  // The paper's user faces the drone; a user who turned their back may still stretch out an arm (pointing
  // something out to someone), and BlazePose reads a back view as a front one (hands README). A user whose
  // face the cascade has found before (at the track's start or a re-check), missed at away_misses re-checks in
  // a row where a face of at least away_min_face_px should be (the cascade finds the synthetic user's face as
  // shot to 4.5 m at 640x480, 23 px: TrackerRange), is turned away (user_track_t.FACING_AWAY): the hands stage
  // reads no command from them. After a miss the face is re-checked again after weak_recheck_frames, so a
  // user who turns back is seen within a few frames. 0: off.
  int away_misses = 2;
  double away_min_face_px = 24.0;
  double torso_colour_rate = 0.2;
  int torso_colour_bins = 8;
  double torso_dark_level = 20.0;

  template <class V>
  void visit(V& v) {
    v.group("face", face);
    v.group("dsst", dsst);
    v.group("body_fit", body_fit);
    v.group("person", person);
    v("body_width_in_faces", body_width_in_faces, 0.5, 20.0, "head-body ratio: body box width / face width");
    v("body_height_in_faces", body_height_in_faces, 0.5, 20.0, "head-body ratio: body box height / face height");
    v("body_top_in_faces", body_top_in_faces, 0.0, 5.0, "body box top above the face top, in face heights");
    v("lost_psr", lost_psr, 0.0, 100.0, "peak-to-sidelobe ratio below which a frame is bad");
    v("lost_frames", lost_frames, 1, 1000, "consecutive bad frames before the track is LOST");
    v("learn_psr", learn_psr, 0.0, 100.0, "a frame is learnt only when its PSR is at least this");
    v("redetect_psr", redetect_psr, 0.0, 100.0, "LOST: the last good filter re-finds the target at this PSR (0: never)");
    v("redetect_frames", redetect_frames, 1, 1000, "LOST: frames in a row at redetect_psr to re-find the target");
    v("lost_search_frames", lost_search_frames, 1, 100000, "frames LOST (last box kept, re-detection) before SEARCHING");
    v("search_full_stride", search_full_stride, 1, 1000, "not tracking: search the whole frame every this many frames");
    v("search_local_scale", search_local_scale, 1.0, 10.0, "LOST: the face search window, the last box grown by this");
    v("lost_scan_face_growth", lost_scan_face_growth, 0.0, 100.0, "LOST: scan the whole frame only if the user's last face grown by this could be found there, and search around the last box for faces up to that size (0: always, any size)");
    v("camera_queue", camera_queue, 1, 1000, "CAMERA frames queued at most (more are skipped, counted in HEALTH.dropped)");
    v("opencv_threads", opencv_threads, -1, 64, "cv::setNumThreads of the stage's process (0: no worker threads, -1: OpenCV's default)");
    v("face_recheck_frames", face_recheck_frames, 0, 100000, "re-find the face in the box this often, frames (0: never, as the paper)");
    v("face_recheck_tolerance", face_recheck_tolerance, 0.0, 1.0, "re-anchor when box and face disagree by more, fraction of box width");
    v("face_recheck_tolerance_px", face_recheck_tolerance_px, 0.0, 100.0, "... and resize only when the face's width differs by more than this, pixels of the searched image");
    v("manual_box_keeps_shape", manual_box_keeps_shape, "a manual box keeps its shape, the ratios measured on the first face its re-check finds (false: re-anchored on the preset body box of that face)");
    v("face_recheck_min_share", face_recheck_min_share, 0.5, 1.0, "re-check: smallest face searched, share of the expected face width");
    v("face_recheck_max_step", face_recheck_max_step, 0.0, 10.0, "a re-check changes the box's size by at most this share, the rest at the next re-check, due after weak_recheck_frames (0: no limit)");
    v("face_recheck_misses", face_recheck_misses, 0, 1000, "face missed (with weak PSR) at this many re-checks in a row: LOST (0: never)");
    v("face_miss_psr", face_miss_psr, 0.0, 1000.0, "a re-check miss counts only when the frame's PSR is below this");
    v("recheck_min_torso_match", recheck_min_torso_match, 0.0, 1.0, "re-check: a face whose torso colours match the track's less is not the user's (0: off)");
    v("user_memory_frames", user_memory_frames, 0, 1000000, "frames SEARCHING during which a face must still wear the lost user's clothes (0 = any face)");
    v("weak_recheck_frames", weak_recheck_frames, 1, 100000, "a track that knows the user's clothes is re-checked this often while PSR < weak_recheck_psr, frames");
    v("weak_recheck_psr", weak_recheck_psr, 0.0, 1000.0, "PSR below which such a track is re-checked every weak_recheck_frames (0: never early)");
    v("away_misses", away_misses, 0, 1000, "a user whose face was found before, missed at this many re-checks in a row: turned away, no command read (0: off)");
    v("away_min_face_px", away_min_face_px, 0.0, 1000.0, "... only where the face the box expects is at least this wide, pixels (smaller: facing unknown)");
    v("recheck_other_clothes", recheck_other_clothes, "a torso more like the clothes last found in the user's place than the user's is not the user's");
    v("torso_colour_rate", torso_colour_rate, 0.0, 1.0, "blend rate of the track's torso colours at each matching re-check");
    v("torso_colour_bins", torso_colour_bins, 2, 64, "torso colours: chromaticity bins per axis");
    v("torso_dark_level", torso_dark_level, 0.0, 255.0, "torso colours: pixels with a mean level below this are not read");
  }
};

// The tracker's section of the config file (services/system assembles the whole file from every stage's).
inline void add_tracker_sections(ConfigSchema& schema) { schema.section<TrackerParams>("tracker"); }

}  // namespace gpilot
