// gpilot.image_t <-> cv::Mat. Decoding validates everything (sizes, stride, format, JPEG content): a bad
// image yields a reason, never a crash or a Mat that reads past its buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "gpilot/image_t.hpp"
#include "image_codec_params.hpp"

namespace gpilot {

// On success out is CV_8UC3 (BGR8, JPEG) or CV_8UC1 (GRAY8) and the result is "". Raw formats are
// wrapped without a copy: out shares msg.data and must not outlive msg. JPEG is decoded into out, only after
// its header's size matched the message's and both are within limits (nothing is decoded otherwise).
std::string image_to_mat(const image_t& msg, cv::Mat& out, const ImageLimits& limits = ImageLimits{});

// A baseline/progressive JPEG's size from its first SOF marker, without decoding: "" and width/height set, or
// why the bytes are not a JPEG whose size can be read (no SOI, a segment past the end, no SOF before SOS).
std::string jpeg_dimensions(const uint8_t* data, size_t size, int& width, int& height);

// A source's own JPEG (an MJPEG video's frame, a webcam's MJPEG buffer) as a JPEG image_t, without decoding
// its pixels: "" and `out` filled, or why the bytes are not a JPEG the stages could decode (its header is read
// by the same decoder they use).
std::string jpeg_to_image(const uint8_t* data, size_t size, int64_t utime, int64_t seq, image_t& out);

// JPEG chroma subsampling: 4:4:4 keeps every pixel's colour (a 10 px hand square at 10 m keeps its skin
// colour), 4:2:0 halves chroma both ways (smaller files, colour smeared over 2x2 pixels).
enum class JpegChroma { k444, k422, k420 };
// "444" / "422" / "420" -> JpegChroma; false for another name.
bool jpeg_chroma_from_name(const std::string& name, JpegChroma& out);

// Encodes a CV_8UC3 (BGR) or CV_8UC1 frame. For PIXEL_FORMAT_JPEG a grey frame is stored as grey JPEG
// (libjpeg-turbo's TurboJPEG API, the decoder's library). Throws std::invalid_argument for an empty frame or
// an unsupported type.
image_t mat_to_image(const cv::Mat& frame, int64_t utime, int64_t seq, int8_t pixel_format = image_t::PIXEL_FORMAT_BGR8,
                     int jpeg_quality = 90, JpegChroma chroma = JpegChroma::k420);

// "BGR8" / "GRAY8" / "JPEG" -> PIXEL_FORMAT_*, or -1.
int8_t pixel_format_from_name(const std::string& name);

}  // namespace gpilot
