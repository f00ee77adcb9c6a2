// Fuzz target: the tracker core (UserTracker) fed a sequence of small frames, manual boxes (TRACKER_INIT, as
// check_message lets them through) and resets, as gpilot-tracker feeds it. Each input is one sequence on a
// fresh tracker. Whatever it publishes must be a USER_TRACK that check_message accepts (what hands takes).
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "face_cascade.hpp"
#include "fuzz_input.hpp"
#include "message_checks.hpp"
#include "stage_frames.hpp"
#include "tracker_service.hpp"
#include "user_tracker.hpp"

namespace {

// The frame's message as far as USER_TRACK copies it (its size; no pixels).
gpilot::image_t header_of(const cv::Mat& frame) {
  gpilot::image_t m{};
  m.width = frame.cols;
  m.height = frame.rows;
  return m;
}

// Small frames, small models: the defaults' model sizes (1200..2500 px, 33 scales) would spend the fuzzer's
// time resampling a 48 px frame up to them. These are in the config's ranges; the code paths are the same.
gpilot::TrackerParams params() {
  gpilot::TrackerParams p;
  p.dsst.number_of_scales = 5;
  p.dsst.min_model_area = 64;
  p.dsst.max_model_area = 256;
  p.dsst.scale_model_max_area = 64;
  p.face_recheck_frames = 3;  // the re-check and re-anchoring within a short sequence
  p.lost_frames = 2;
  return p;
}

const gpilot::UserTracker& prototype() {
  // The Haar cascade loads once; each sequence runs on a copy of the untouched tracker.
  static const gpilot::UserTracker t{params(), gpilot::load_tracker_models(params())};
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  gpilot::fuzz::Input in(data, size);
  gpilot::UserTracker tracker = prototype();
  for (int step = 0; step < 6 && !in.empty(); ++step) {
    const uint8_t op = in.byte() % 4;
    if (op == 0) {
      gpilot::tracker_init_t m{};
      m.command = gpilot::tracker_init_t::COMMAND_SET_BOX;
      for (float& v : m.box) v = in.coordinate() / 8.0f;  // small frames: boxes of a few to 256 px
      if (!gpilot::check_message(m).empty()) continue;    // rejected by BusNode before the tracker
      (void)tracker.set_box(cv::Rect2d(m.box[0], m.box[1], m.box[2], m.box[3]));
    } else if (op == 1) {
      tracker.reset();
    } else {
      cv::Mat frame = gpilot::fuzz::frame(in, 4, 48);
      if (in.flag()) cv::cvtColor(frame, frame, cv::COLOR_BGR2GRAY);
      gpilot::TrackOutput out;
      try {
        out = tracker.process(frame);
      } catch (const std::invalid_argument&) {
        continue;  // the service rejects the frame and the track is unchanged
      }
      const std::string why = gpilot::check_message(gpilot::to_message(out, header_of(frame)));
      if (!why.empty()) gpilot::fuzz::fail("the tracker published a USER_TRACK that is rejected: " + why);
    }
  }
  return 0;
}
