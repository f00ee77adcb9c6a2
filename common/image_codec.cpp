#include "image_codec.hpp"

#include <cstring>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "message_checks.hpp"

namespace gpilot {

std::string image_to_mat(const image_t& msg, cv::Mat& out) {
  out.release();
  const std::string why = check_message(msg);
  if (!why.empty()) return why;
  if (msg.pixel_format == image_t::PIXEL_FORMAT_JPEG) {
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
      return "JPEG decodes to " + std::to_string(decoded.cols) + "x" + std::to_string(decoded.rows) +
             " but the message says " + std::to_string(msg.width) + "x" + std::to_string(msg.height);
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
