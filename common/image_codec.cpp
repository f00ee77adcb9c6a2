#include "image_codec.hpp"

#include <cstring>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "message_checks.hpp"

namespace gpilot {

std::string jpeg_dimensions(const uint8_t* data, size_t size, int& width, int& height) {
  width = height = 0;
  if (size < 4 || data[0] != 0xFF || data[1] != 0xD8) return "JPEG data does not start with an SOI marker";
  size_t pos = 2;
  // Marker segments by their lengths, as libjpeg reads them; anything else before the frame header (stray
  // bytes, which libjpeg would skip with a warning) is a rejection: no size is trusted that libjpeg might
  // read differently.
  while (pos < size) {
    if (data[pos] != 0xFF) return "JPEG data has stray bytes before its frame header";
    while (pos < size && data[pos] == 0xFF) ++pos;  // fill bytes
    if (pos >= size) break;
    const uint8_t marker = data[pos++];
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // TEM, RSTn: no length
    if (marker == 0xD8 || marker == 0xD9 || marker == 0xDA || marker == 0x00)
      return "JPEG data has no frame header (SOF) before its scan";
    if (pos + 2 > size) break;
    const size_t length = (static_cast<size_t>(data[pos]) << 8) | data[pos + 1];  // includes its own 2 bytes
    if (length < 2 || pos + length > size) return "JPEG marker segment runs past the end of the data";
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (length < 8) return "JPEG frame header (SOF) is too short";
      height = (data[pos + 3] << 8) | data[pos + 4];
      width = (data[pos + 5] << 8) | data[pos + 6];
      if (width == 0 || height == 0) return "JPEG frame header gives no size (a DNL height is not supported)";
      return "";
    }
    pos += length;
  }
  return "JPEG data ends before its frame header (SOF)";
}

std::string image_to_mat(const image_t& msg, cv::Mat& out, const ImageLimits& limits) {
  out.release();
  const std::string why = check_message(msg);
  if (!why.empty()) return why;
  const auto dims = [](int w, int h) { return std::to_string(w) + "x" + std::to_string(h); };
  if (msg.width > limits.max_width || msg.height > limits.max_height)
    return "image is " + dims(msg.width, msg.height) + ", larger than image.max_width x image.max_height (" +
           dims(limits.max_width, limits.max_height) + ")";
  if (msg.pixel_format == image_t::PIXEL_FORMAT_JPEG) {
    // The size in the JPEG's header, before any pixel is decoded: a 928-byte datagram claiming 16384x16384
    // would otherwise cost a second of decoding and 800 MB before the size comparison below refused it.
    int header_w = 0, header_h = 0;
    const std::string bad_header = jpeg_dimensions(msg.data.data(), msg.data.size(), header_w, header_h);
    if (!bad_header.empty()) return bad_header;
    if (header_w != msg.width || header_h != msg.height)
      return "JPEG header says " + dims(header_w, header_h) + " but the message says " + dims(msg.width, msg.height);
    cv::Mat decoded;
    try {
      decoded = cv::imdecode(cv::Mat(1, msg.size, CV_8UC1, const_cast<uint8_t*>(msg.data.data())), cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception&) {
      decoded.release();
    }
    if (decoded.empty()) return "JPEG data does not decode";
    if (decoded.depth() != CV_8U || (decoded.channels() != 1 && decoded.channels() != 3))
      return "JPEG decodes to an unsupported pixel type";
    if (decoded.cols != msg.width || decoded.rows != msg.height)
      return "JPEG decodes to " + dims(decoded.cols, decoded.rows) + " but the message says " +
             dims(msg.width, msg.height);
    if (decoded.channels() == 1) cv::cvtColor(decoded, decoded, cv::COLOR_GRAY2BGR);
    out = decoded;
    return "";
  }
  const int type = msg.pixel_format == image_t::PIXEL_FORMAT_GRAY8 ? CV_8UC1 : CV_8UC3;
  out = cv::Mat(msg.height, msg.width, type, const_cast<uint8_t*>(msg.data.data()), static_cast<size_t>(msg.row_stride));
  return "";
}

image_t mat_to_image(const cv::Mat& frame, int64_t utime, int64_t seq, int8_t pixel_format, int jpeg_quality) {
  if (frame.empty()) throw std::invalid_argument("mat_to_image: empty frame");
  if (frame.type() != CV_8UC3 && frame.type() != CV_8UC1)
    throw std::invalid_argument("mat_to_image: frame must be 8-bit BGR or grey");
  image_t msg;
  msg.utime = utime;
  msg.seq = seq;
  msg.width = frame.cols;
  msg.height = frame.rows;
  if (pixel_format == image_t::PIXEL_FORMAT_JPEG) {
    std::vector<uint8_t> bytes;
    cv::imencode(".jpg", frame, bytes, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
    msg.row_stride = 0;
    msg.pixel_format = image_t::PIXEL_FORMAT_JPEG;
    msg.data = std::move(bytes);
  } else {
    cv::Mat conv = frame;
    if (pixel_format == image_t::PIXEL_FORMAT_GRAY8 && frame.channels() == 3)
      cv::cvtColor(frame, conv, cv::COLOR_BGR2GRAY);
    else if (pixel_format == image_t::PIXEL_FORMAT_BGR8 && frame.channels() == 1)
      cv::cvtColor(frame, conv, cv::COLOR_GRAY2BGR);
    else if (pixel_format != image_t::PIXEL_FORMAT_GRAY8 && pixel_format != image_t::PIXEL_FORMAT_BGR8)
      throw std::invalid_argument("mat_to_image: unknown pixel format " + std::to_string(pixel_format));
    msg.pixel_format = pixel_format;
    const size_t row = conv.cols * conv.elemSize();
    msg.row_stride = static_cast<int32_t>(row);
    msg.data.resize(row * conv.rows);
    for (int y = 0; y < conv.rows; ++y) std::memcpy(msg.data.data() + y * row, conv.ptr(y), row);
  }
  msg.size = static_cast<int32_t>(msg.data.size());
  return msg;
}

int8_t pixel_format_from_name(const std::string& name) {
  if (name == "BGR8") return image_t::PIXEL_FORMAT_BGR8;
  if (name == "GRAY8") return image_t::PIXEL_FORMAT_GRAY8;
  if (name == "JPEG") return image_t::PIXEL_FORMAT_JPEG;
  return -1;
}

}  // namespace gpilot
