#include "h264_writer.hpp"

#include <algorithm>
#include <stdexcept>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace gpilot {
namespace {

std::string av_error(int err) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(err, text, sizeof text);
  return text;
}

}  // namespace

H264Writer::~H264Writer() {
  try {
    close();
  } catch (const std::exception&) {
    release();  // a destructor does not throw; close() reports to whoever calls it
  }
}

std::string H264Writer::open(const std::string& path, cv::Size size, double fps, const H264Params& params) {
  release();
  if (size.width <= 0 || size.height <= 0 || size.width % 2 || size.height % 2)
    return "frame size " + std::to_string(size.width) + "x" + std::to_string(size.height) + " is not even";
  if (!(fps > 0)) return "frame rate must be positive";
  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (!codec) return "FFmpeg has no libx264 encoder";
  const auto fail = [&](const std::string& why) {
    release();
    return why;
  };
  int err = avformat_alloc_output_context2(&format_, nullptr, "mp4", path.c_str());
  if (err < 0 || !format_) return fail("no MP4 muxer: " + av_error(err));
  stream_ = avformat_new_stream(format_, nullptr);
  codec_ = avcodec_alloc_context3(codec);
  frame_ = av_frame_alloc();
  packet_ = av_packet_alloc();
  if (!stream_ || !codec_ || !frame_ || !packet_) return fail("out of memory");

  const AVRational rate = av_d2q(fps, 100000);
  codec_->width = size.width;
  codec_->height = size.height;
  codec_->pix_fmt = AV_PIX_FMT_YUV420P;
  codec_->framerate = rate;
  codec_->time_base = av_inv_q(rate);
  codec_->gop_size = std::max(1, static_cast<int>(2 * fps));  // a key frame every 2 s: the video seeks
  codec_->thread_count = params.threads;
  if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* options = nullptr;
  av_dict_set(&options, "preset", params.preset.c_str(), 0);
  av_dict_set(&options, "crf", std::to_string(params.crf).c_str(), 0);
  err = avcodec_open2(codec_, codec, &options);
  const bool unused = av_dict_count(options) > 0;  // an option libx264 does not know
  av_dict_free(&options);
  if (err < 0) return fail("libx264 does not open (preset " + params.preset + "): " + av_error(err));
  if (unused) return fail("libx264 does not take preset '" + params.preset + "' or crf " + std::to_string(params.crf));
  if ((err = avcodec_parameters_from_context(stream_->codecpar, codec_)) < 0) return fail(av_error(err));
  stream_->time_base = codec_->time_base;
  stream_->avg_frame_rate = rate;

  frame_->format = codec_->pix_fmt;
  frame_->width = size.width;
  frame_->height = size.height;
  if ((err = av_frame_get_buffer(frame_, 0)) < 0) return fail(av_error(err));
  to_yuv_ = sws_getContext(size.width, size.height, AV_PIX_FMT_BGR24, size.width, size.height, AV_PIX_FMT_YUV420P,
                           SWS_BILINEAR, nullptr, nullptr, nullptr);
  if (!to_yuv_) return fail("no BGR to YUV 4:2:0 conversion");

  if ((err = avio_open(&format_->pb, path.c_str(), AVIO_FLAG_WRITE)) < 0) return fail(path + ": " + av_error(err));
  AVDictionary* mux = nullptr;
  av_dict_set(&mux, "movflags", "+faststart", 0);  // the index first: a browser plays it while loading
  err = avformat_write_header(format_, &mux);
  av_dict_free(&mux);
  if (err < 0) return fail(path + ": " + av_error(err));
  size_ = size;
  next_pts_ = 0;
  return "";
}

void H264Writer::write(const cv::Mat& bgr) {
  if (!is_open()) throw std::runtime_error("H264Writer::write: not open");
  if (bgr.type() != CV_8UC3 || bgr.size() != size_) throw std::runtime_error("H264Writer::write: not a BGR frame of the opened size");
  int err = av_frame_make_writable(frame_);
  if (err < 0) throw std::runtime_error("H264Writer: " + av_error(err));
  const uint8_t* src[1] = {bgr.data};
  const int src_stride[1] = {static_cast<int>(bgr.step)};
  sws_scale(to_yuv_, src, src_stride, 0, bgr.rows, frame_->data, frame_->linesize);
  frame_->pts = next_pts_++;
  if ((err = avcodec_send_frame(codec_, frame_)) < 0) throw std::runtime_error("H264Writer: encoder: " + av_error(err));
  drain();
}

void H264Writer::drain() {
  for (;;) {
    const int err = avcodec_receive_packet(codec_, packet_);
    if (err == AVERROR(EAGAIN) || err == AVERROR_EOF) return;
    if (err < 0) throw std::runtime_error("H264Writer: encoder: " + av_error(err));
    av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
    packet_->stream_index = stream_->index;
    const int w = av_interleaved_write_frame(format_, packet_);  // takes the packet's data, resets it
    if (w < 0) throw std::runtime_error("H264Writer: writing: " + av_error(w));
  }
}

void H264Writer::close() {
  if (!is_open()) return;
  // Whatever happens below, everything is freed; the first failure is reported.
  std::string why;
  try {
    int err = avcodec_send_frame(codec_, nullptr);
    if (err < 0) throw std::runtime_error("H264Writer: flushing: " + av_error(err));
    drain();
    if ((err = av_write_trailer(format_)) < 0) throw std::runtime_error("H264Writer: index: " + av_error(err));
  } catch (const std::exception& e) {
    why = e.what();
  }
  release();
  if (!why.empty()) throw std::runtime_error(why);
}

void H264Writer::release() {
  if (format_ && format_->pb) avio_closep(&format_->pb);
  avformat_free_context(format_);  // frees stream_ too
  format_ = nullptr;
  stream_ = nullptr;
  avcodec_free_context(&codec_);
  av_frame_free(&frame_);
  av_packet_free(&packet_);
  sws_freeContext(to_yuv_);
  to_yuv_ = nullptr;
}

}  // namespace gpilot
