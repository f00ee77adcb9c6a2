// MAVLink v2 frame encoder and parser.
#include "frame.hpp"

#include <stdexcept>
#include <string>

#include "crc.hpp"
#include "messages.hpp"
#include "signing.hpp"

namespace gpilot::mavlink {

std::vector<uint8_t> encode_frame(const Frame& frame) {
  const MessageInfo* info = message_info(frame.msgid);
  if (!info) throw std::invalid_argument("MAVLink message id " + std::to_string(frame.msgid) + " is not known");
  size_t n = std::min<size_t>(frame.payload.size(), info->length);
  while (n > 1 && frame.payload[n - 1] == 0) --n;  // v2: trailing zeros are not sent (at least one byte stays)
  std::vector<uint8_t> out;
  out.reserve(kHeaderLength + n + 2);
  out.push_back(kMagicV2);
  out.push_back(static_cast<uint8_t>(n));
  out.push_back(0);  // incompat flags: not signed
  out.push_back(0);  // compat flags
  out.push_back(frame.seq);
  out.push_back(frame.sysid);
  out.push_back(frame.compid);
  out.push_back(static_cast<uint8_t>(frame.msgid));
  out.push_back(static_cast<uint8_t>(frame.msgid >> 8));
  out.push_back(static_cast<uint8_t>(frame.msgid >> 16));
  out.insert(out.end(), frame.payload.begin(), frame.payload.begin() + static_cast<long>(n));
  uint16_t crc = crc_x25(out.data() + 1, out.size() - 1);
  crc = crc_accumulate(info->crc_extra, crc);
  out.push_back(static_cast<uint8_t>(crc));
  out.push_back(static_cast<uint8_t>(crc >> 8));
  return out;
}

void FrameParser::drop(size_t n) { buf_.erase(buf_.begin(), buf_.begin() + static_cast<long>(n)); }

void FrameParser::end_of_datagram() {
  if (buf_.empty()) return;
  ++counts_.truncated;
  last_reject_ = "datagram ends inside a frame";
  buf_.clear();
}

void FrameParser::feed(const uint8_t* data, size_t n, const std::function<void(const Frame&)>& on_frame) {
  buf_.insert(buf_.end(), data, data + n);
  while (!buf_.empty()) {
    if (buf_[0] != kMagicV2) {
      ++counts_.skipped_bytes;
      drop(1);
      continue;
    }
    if (buf_.size() < kHeaderLength) return;
    const uint8_t len = buf_[1];
    const uint8_t incompat = buf_[2];
    const size_t total = kHeaderLength + len + 2 + ((incompat & kIncompatSigned) ? kSignatureLength : 0);
    if (incompat & ~kIncompatSigned) {
      // Flags we do not understand change the frame's layout: it cannot be read; resynchronise.
      ++counts_.unsupported;
      last_reject_ = "unknown incompatibility flags";
      drop(1);
      continue;
    }
    const uint32_t msgid = buf_[7] | (buf_[8] << 8) | (static_cast<uint32_t>(buf_[9]) << 16);
    const MessageInfo* info = message_info(msgid);
    if (info && len > info->length) {
      ++counts_.bad_length;
      last_reject_ = "payload longer than the message";
      drop(1);
      continue;
    }
    if (buf_.size() < total) return;
    if (!info) {
      ++counts_.unknown_id;
      last_reject_ = "unknown message id";
      drop(total);
      continue;
    }
    uint16_t crc = crc_x25(buf_.data() + 1, kHeaderLength - 1 + len);
    crc = crc_accumulate(info->crc_extra, crc);
    const uint16_t got = static_cast<uint16_t>(buf_[kHeaderLength + len] | (buf_[kHeaderLength + len + 1] << 8));
    if (crc != got) {
      ++counts_.bad_crc;
      last_reject_ = "bad CRC";
      drop(1);
      continue;
    }
    if ((incompat & kIncompatSigned) && !checker_) {
      // We hold no signing key, so a signature cannot be checked: such frames are not trusted.
      ++counts_.unsupported;
      last_reject_ = "signed frame (no key to check it)";
      drop(total);
      continue;
    }
    if (checker_ && !(incompat & kIncompatSigned)) {
      ++counts_.unsigned_frames;
      last_reject_ = "unsigned frame (mavlink.signing_key is set: every frame must be signed)";
      drop(total);
      continue;
    }
    if (checker_) {
      if (const char* why = checker_->check(buf_.data(), total)) {
        ++counts_.bad_signature;
        last_reject_ = why;
        drop(total);
        continue;
      }
    }
    Frame f;
    f.seq = buf_[4];
    f.sysid = buf_[5];
    f.compid = buf_[6];
    f.msgid = msgid;
    f.payload.assign(buf_.begin() + kHeaderLength, buf_.begin() + static_cast<long>(kHeaderLength + len));
    f.payload.resize(info->length, 0);
    ++counts_.frames;
    drop(total);
    on_frame(f);
  }
}

}  // namespace gpilot::mavlink
