// Fuzz target: image_to_mat on JPEG and raw frames built from the input (the image_t fields as the decoder
// would hand them over, without the wire format in the way). A JPEG's size is taken from the message, or,
// half of the time, from the JPEG's own header so the fuzzer gets past the size check into libjpeg. The
// result must be a frame of the message's size whose every pixel can be read, or a reason.
#include <algorithm>
#include <cstdint>

#include <opencv2/core.hpp>

#include "fuzz_input.hpp"
#include "image_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  gpilot::fuzz::Input in(data, size);
  gpilot::image_t msg{};
  msg.utime = in.raw<int64_t>();
  msg.seq = in.raw<int64_t>();
  const uint8_t mode = in.byte();
  msg.pixel_format = static_cast<int8_t>(mode & 3 ? (mode & 3) : in.byte());  // 1 GRAY8, 2 BGR8, 3 JPEG, or any
  msg.width = in.flag() ? in.raw<int32_t>() : static_cast<int32_t>(in.in(0, 300));
  msg.height = in.flag() ? in.raw<int32_t>() : static_cast<int32_t>(in.in(0, 300));
  const int64_t row = static_cast<int64_t>(msg.width) * (msg.pixel_format == 2 ? 3 : 1) + in.byte() % 8;
  msg.row_stride = in.flag() ? in.raw<int32_t>() : static_cast<int32_t>(std::clamp<int64_t>(row, INT32_MIN, INT32_MAX));
  msg.data = in.rest();
  msg.size = (mode & 4) ? static_cast<int32_t>(msg.data.size()) + (mode >> 5) - 4 : static_cast<int32_t>(msg.data.size());
  if (msg.pixel_format == gpilot::image_t::PIXEL_FORMAT_JPEG && (mode & 8)) {
    int w = 0, h = 0;
    if (gpilot::jpeg_dimensions(msg.data.data(), msg.data.size(), w, h).empty()) msg.width = w, msg.height = h;
  }
  gpilot::ImageLimits limits;
  limits.max_width = limits.max_height = 256;
  cv::Mat out;
  if (!gpilot::image_to_mat(msg, out, limits).empty()) {
    if (!out.empty()) gpilot::fuzz::fail("a rejected image left a frame behind");
    return 0;
  }
  if (out.cols != msg.width || out.rows != msg.height) gpilot::fuzz::fail("image_to_mat gave another size");
  if (out.type() != CV_8UC3 && out.type() != CV_8UC1) gpilot::fuzz::fail("image_to_mat gave another pixel type");
  unsigned sum = 0;
  for (int y = 0; y < out.rows; ++y) {
    const uint8_t* p = out.ptr<uint8_t>(y);
    for (size_t x = 0; x < out.cols * out.elemSize(); ++x) sum += p[x];
  }
  (void)sum;
  return 0;
}
