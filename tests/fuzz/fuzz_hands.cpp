// Fuzz target: the hands stage core fed a sequence of small frames (raw or JPEG) and USER_TRACKs (as
// check_message lets them through), pair by pair as gpilot-hands takes them (hands_on_pair: decode, size
// check, the method make_hand_method builds: the input's first byte picks pose or skin). Each input is one sequence on
// a reset method. Whatever it publishes must be a HAND_OBS that check_message accepts (what decide takes).
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "fuzz_input.hpp"
#include "hands/hands_core_factory.hpp"
#include "hands/hands_params.hpp"
#include "hands/hands_service.hpp"
#include "image_codec.hpp"
#include "message_checks.hpp"
#include "stage_frames.hpp"

namespace {

gpilot::HandMethod& method(const std::string& name) {
  static std::map<std::string, std::unique_ptr<gpilot::HandMethod>> built;
  auto& m = built[name];
  if (!m) {
    gpilot::HandsParams params;
    params.method = name;
    m = gpilot::make_hand_method(params);
  }
  return *m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  gpilot::fuzz::Input in(data, size);
  gpilot::HandMethod& obs_core = method(in.flag() ? "pose" : "skin");
  obs_core.reset();
  gpilot::ImageLimits limits;
  limits.max_width = limits.max_height = 256;
  for (int step = 0; step < 5 && !in.empty(); ++step) {
    const cv::Mat bgr = gpilot::fuzz::frame(in, 4, 64);
    const bool jpeg = in.byte() < 32;
    const gpilot::image_t frame = gpilot::mat_to_image(
        bgr, step, step, jpeg ? gpilot::image_t::PIXEL_FORMAT_JPEG : gpilot::image_t::PIXEL_FORMAT_BGR8, 80);
    gpilot::user_track_t track{};
    track.seq = step;
    track.status = static_cast<int8_t>(in.byte() % 3);
    track.track_id = static_cast<int32_t>(in.in(0, 3));
    const uint8_t sizes = in.byte();
    track.image_width = sizes < 240 ? bgr.cols : static_cast<int32_t>(in.in(-1, 200));
    track.image_height = sizes < 240 ? bgr.rows : static_cast<int32_t>(in.in(-1, 200));
    for (float& v : track.box) v = in.coordinate() / 16.0f;
    if (in.flag()) {
      for (float& v : track.face_box) v = in.coordinate() / 16.0f;
    }
    track.confidence = in.coordinate();
    track.init_source = static_cast<int8_t>(in.byte() % 3);
    if (!gpilot::check_message(track).empty()) continue;  // rejected by BusNode before the stage
    gpilot::hand_obs_t out;
    if (!gpilot::hands_on_pair(obs_core, frame, track, limits, out).empty()) continue;
    const std::string why = gpilot::check_message(out);
    if (!why.empty()) gpilot::fuzz::fail("hands published a HAND_OBS that is rejected: " + why);
  }
  return 0;
}
