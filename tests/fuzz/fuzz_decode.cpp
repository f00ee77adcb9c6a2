// Fuzz target: one datagram through BusNode's decode-and-check path for any lcmtype (decode_exactly: the
// wire-length walk, LCM's decoder, trailing bytes; then check_message), and an image that passes on through
// image_to_mat as the tracker and hands stages take it. Any input must give a verdict, never a crash; a
// message that decodes must encode back to the same bytes (nothing was invented or lost in the decoding).
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "bus_node.hpp"
#include "fuzz_input.hpp"
#include "image_codec.hpp"

namespace {

template <class Msg>
void one(const uint8_t* data, size_t size) {
  Msg msg;
  if (!gpilot::decode_exactly(data, size, msg).empty()) return;
  const int n = msg.getEncodedSize();
  if (n != static_cast<int>(size))
    gpilot::fuzz::fail(std::string("gpilot.") + Msg::getTypeName() + " decoded from " + std::to_string(size) +
                       " bytes re-encodes to " + std::to_string(n));
  const std::string why = gpilot::check_message(msg);
  if constexpr (std::is_same_v<Msg, gpilot::image_t>) {
    if (!why.empty()) return;
    gpilot::ImageLimits limits;  // small, so the fuzzer's time goes to the checks, not to decoding big frames
    limits.max_width = limits.max_height = 256;
    cv::Mat out;
    if (!gpilot::image_to_mat(msg, out, limits).empty()) return;
    unsigned sum = 0;  // every pixel read in instrumented code: a Mat past its buffer shows here
    for (int y = 0; y < out.rows; ++y) {
      const uint8_t* p = out.ptr<uint8_t>(y);
      for (size_t x = 0; x < out.cols * out.elemSize(); ++x) sum += p[x];
    }
    if (out.cols != msg.width || out.rows != msg.height) gpilot::fuzz::fail("image_to_mat gave another size");
    (void)sum;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // First byte: the channel's type (a BusNode subscription decodes one type); the rest is the datagram.
  if (size == 0) return 0;
  const uint8_t type = data[0] % 12;
  ++data, --size;
  switch (type) {
    case 0: one<gpilot::image_t>(data, size); break;
    case 1: one<gpilot::tracker_init_t>(data, size); break;
    case 2: one<gpilot::user_track_t>(data, size); break;
    case 3: one<gpilot::hand_obs_t>(data, size); break;
    case 4: one<gpilot::gesture_cmd_t>(data, size); break;
    case 5: one<gpilot::flight_control_t>(data, size); break;
    case 6: one<gpilot::flight_setpoint_t>(data, size); break;
    case 7: one<gpilot::vehicle_state_t>(data, size); break;
    case 8: one<gpilot::ground_truth_t>(data, size); break;
    case 9: one<gpilot::health_t>(data, size); break;
    case 10: one<gpilot::config_t>(data, size); break;
    default: one<gpilot::autopilot_t>(data, size); break;
  }
  return 0;
}
