#include "image_codec.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <turbojpeg.h>

#include "message_checks.hpp"

namespace gpilot {

namespace {

// One TurboJPEG handle of each kind per thread, made on first use: making one allocates libjpeg's state (~30 kB),
// and capture encodes, every stage decodes, every frame.
template <tjhandle (*Make)()>
tjhandle thread_jpeg_handle() {
  struct Handle {
    tjhandle h = Make();
    ~Handle() {
      if (h) tjDestroy(h);
    }
  };
  thread_local Handle handle;
  return handle.h;
}

tjhandle jpeg_decompressor() { return thread_jpeg_handle<tjInitDecompress>(); }
tjhandle jpeg_compressor() { return thread_jpeg_handle<tjInitCompress>(); }

// The header as the stages' decoder reads it: "" and its size, or why they could not decode the JPEG.
std::string decoder_header(tjhandle tj, const uint8_t* data, size_t size, int& width, int& height) {
  int subsamp = 0, colourspace = 0;
  if (tjDecompressHeader3(tj, const_cast<uint8_t*>(data), static_cast<unsigned long>(size), &width, &height, &subsamp,
                          &colourspace) != 0)
    return "JPEG data does not decode";
  if (colourspace == TJCS_CMYK || colourspace == TJCS_YCCK) return "JPEG decodes to an unsupported pixel type";
  return "";
}

}  // namespace

bool jpeg_chroma_from_name(const std::string& name, JpegChroma& out) {
  if (name == "444") out = JpegChroma::k444;
  else if (name == "422") out = JpegChroma::k422;
  else if (name == "420") out = JpegChroma::k420;
  else return false;
  return true;
}

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

std::string jpeg_to_image(const uint8_t* data, size_t size, int64_t utime, int64_t seq, image_t& out) {
  int width = 0, height = 0;
  const std::string bad = jpeg_dimensions(data, size, width, height);
  if (!bad.empty()) return bad;
  tjhandle tj = jpeg_decompressor();
  if (!tj) return "JPEG decoder could not be made";
  int tj_w = 0, tj_h = 0;
  const std::string undecodable = decoder_header(tj, data, size, tj_w, tj_h);
  if (!undecodable.empty()) return undecodable;
  out.utime = utime;
  out.seq = seq;
  out.width = width;
  out.height = height;
  out.row_stride = 0;
  out.pixel_format = image_t::PIXEL_FORMAT_JPEG;
  out.data.assign(data, data + size);
  out.size = static_cast<int32_t>(out.data.size());
  return "";
}

std::string image_to_mat(const image_t& msg, cv::Mat& out, const ImageLimits& limits) {
  // The last decoded frame's buffer is decoded into again when nobody else holds it (a stage that keeps
  // frames, e.g. to pair them with tracks, holds another reference): no fresh 921 kB mapping and its page
  // faults per 640x480 frame. A wrapped raw frame has no buffer of its own (u is null) and is never reused.
  cv::Mat reusable;
  if (out.u != nullptr && out.u->refcount == 1 && out.type() == CV_8UC3 && out.isContinuous()) reusable = out;
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
    // libjpeg-turbo's own API straight into BGR (cv::imdecode decodes through the same library, plus a
    // copy and its codec lookup: 1.9-2.8 ms a 640x480 frame). Same decoder, same default DCT and upsampling:
    // the pixels are the ones cv::imdecode gives (test_image_codec checks it). A warning (corrupt data that
    // libjpeg still decodes) is accepted as cv::imdecode accepts it; an error is a rejection.
    tjhandle tj = jpeg_decompressor();
    if (!tj) return "JPEG decoder could not be made";
    int tj_w = 0, tj_h = 0;
    unsigned char* src = const_cast<uint8_t*>(msg.data.data());
    const unsigned long src_size = static_cast<unsigned long>(msg.data.size());
    const std::string undecodable = decoder_header(tj, src, msg.data.size(), tj_w, tj_h);
    if (!undecodable.empty()) return undecodable;
    if (tj_w != msg.width || tj_h != msg.height)
      return "JPEG decodes to " + dims(tj_w, tj_h) + " but the message says " + dims(msg.width, msg.height);
    cv::Mat decoded = reusable;
    decoded.create(msg.height, msg.width, CV_8UC3);  // reallocates only for another size
    if (tjDecompress2(tj, src, src_size, decoded.data, msg.width, static_cast<int>(decoded.step), msg.height, TJPF_BGR, 0) != 0 &&
        tjGetErrorCode(tj) != TJERR_WARNING)
      return "JPEG data does not decode";
    out = decoded;
    return "";
  }
  const int type = msg.pixel_format == image_t::PIXEL_FORMAT_GRAY8 ? CV_8UC1 : CV_8UC3;
  out = cv::Mat(msg.height, msg.width, type, const_cast<uint8_t*>(msg.data.data()), static_cast<size_t>(msg.row_stride));
  return "";
}

image_t mat_to_image(const cv::Mat& frame, int64_t utime, int64_t seq, int8_t pixel_format, int jpeg_quality,
                     JpegChroma chroma) {
  if (frame.empty()) throw std::invalid_argument("mat_to_image: empty frame");
  if (frame.type() != CV_8UC3 && frame.type() != CV_8UC1)
    throw std::invalid_argument("mat_to_image: frame must be 8-bit BGR or grey");
  image_t msg;
  msg.utime = utime;
  msg.seq = seq;
  msg.width = frame.cols;
  msg.height = frame.rows;
  if (pixel_format == image_t::PIXEL_FORMAT_JPEG) {
    // TurboJPEG, not cv::imencode: OpenCV 4.6 cannot choose the chroma subsampling (4:2:0 always), and
    // this saves its copy and codec lookup. Same library, same default tables and DCT.
    tjhandle tj = jpeg_compressor();
    if (!tj) throw std::runtime_error("mat_to_image: JPEG encoder could not be made");
    const bool grey = frame.channels() == 1;
    const int subsamp = grey ? TJSAMP_GRAY
                             : chroma == JpegChroma::k444 ? TJSAMP_444 : chroma == JpegChroma::k422 ? TJSAMP_422 : TJSAMP_420;
    unsigned char* jpeg = nullptr;
    unsigned long jpeg_size = 0;
    if (tjCompress2(tj, frame.data, frame.cols, static_cast<int>(frame.step), frame.rows, grey ? TJPF_GRAY : TJPF_BGR,
                    &jpeg, &jpeg_size, subsamp, std::clamp(jpeg_quality, 1, 100), 0) != 0) {
      tjFree(jpeg);
      throw std::runtime_error(std::string("mat_to_image: JPEG encoding failed: ") + tjGetErrorStr2(tj));
    }
    msg.data.assign(jpeg, jpeg + jpeg_size);
    tjFree(jpeg);
    msg.row_stride = 0;
    msg.pixel_format = image_t::PIXEL_FORMAT_JPEG;
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
