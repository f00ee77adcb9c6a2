#include "log_reader.hpp"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>

#include "clock.hpp"

namespace gpilot {
namespace {

// An LCM log event: sync word, event number, timestamp, channel length, data length (big-endian), channel,
// data. The limits are LCM's own sanity checks.
constexpr uint32_t kSync = 0xEDA1DA01u;
constexpr int64_t kHeaderBytes = 4 + 8 + 8 + 4 + 4;
constexpr int32_t kMaxChannelLength = 1000;

uint64_t be64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | p[i];
  return v;
}
uint32_t be32(const uint8_t* p) { return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | p[3]; }

}  // namespace

LogReader::LogReader(const std::string& path) : path_(path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw LogError(path + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw LogError(path + ": not a regular file");
  size_ = static_cast<int64_t>(st.st_size);
  if (size_ == 0) throw LogError(path + ": the log is empty (0 bytes)");
  f_ = std::fopen(path.c_str(), "rb");
  if (!f_) throw LogError(path + ": " + std::strerror(errno));
  uint8_t head[4];
  if (std::fread(head, 1, 4, f_) != 4 || be32(head) != kSync) {
    std::fclose(f_);
    f_ = nullptr;
    throw LogError(path + ": not an LCM log (it does not start with the LCM event sync word)");
  }
  std::rewind(f_);
}

LogReader::~LogReader() {
  if (f_) std::fclose(f_);
}

bool LogReader::read_exact(void* dst, size_t n) {
  const size_t got = std::fread(dst, 1, n, f_);
  pos_ += static_cast<int64_t>(got);
  return got == n;
}

bool LogReader::find_sync() {
  uint32_t window = 0;
  int64_t scanned = 0;
  int c;
  while ((c = std::fgetc(f_)) != EOF) {
    ++pos_;
    window = (window << 8) | static_cast<uint32_t>(c);
    if (++scanned >= 4 && window == kSync) return true;
  }
  return false;
}

bool LogReader::next(LogEvent& ev) {
  while (true) {
    const int64_t start = pos_;
    if (start >= size_) return false;
    if (size_ - start < kHeaderBytes) {
      warnings_.push_back("log truncated: " + std::to_string(size_ - start) + " bytes at the end (from byte " +
                          std::to_string(start) + ") are less than an event header; read " +
                          std::to_string(events_) + " events");
      pos_ = size_;
      return false;
    }
    uint8_t h[kHeaderBytes];
    if (!read_exact(h, kHeaderBytes)) return false;
    const bool synced = be32(h) == kSync;
    const int64_t eventnum = static_cast<int64_t>(be64(h + 4));
    const int64_t timestamp = static_cast<int64_t>(be64(h + 12));
    const int32_t channel_len = static_cast<int32_t>(be32(h + 20));
    const int32_t data_len = static_cast<int32_t>(be32(h + 24));
    const int64_t remaining = size_ - pos_;
    const bool sane = synced && channel_len > 0 && channel_len < kMaxChannelLength && data_len >= 0;
    if (sane && int64_t(channel_len) + data_len <= remaining) {
      ev.eventnum = eventnum;
      ev.timestamp = timestamp;
      ev.channel.assign(static_cast<size_t>(channel_len), '\0');
      ev.data.resize(static_cast<size_t>(data_len));
      if (!read_exact(&ev.channel[0], static_cast<size_t>(channel_len)) ||
          (data_len > 0 && !read_exact(ev.data.data(), static_cast<size_t>(data_len))))
        return false;
      ++events_;
      return true;
    }
    // Not a whole event here: a cut-off last event, or corrupt bytes. Look for the next sync word after
    // this one; if there is none, the log ends here.
    std::fseek(f_, static_cast<long>(start + 1), SEEK_SET);
    pos_ = start + 1;
    if (!find_sync()) {
      const bool cut = sane && int64_t(channel_len) + data_len > remaining;
      warnings_.push_back(std::string(cut ? "log truncated" : "log has a corrupt tail") + ": the event at byte " +
                          std::to_string(start) + " is incomplete (" + std::to_string(size_ - start) +
                          " bytes left); read " + std::to_string(events_) + " events");
      skipped_ += size_ - start;
      pos_ = size_;
      return false;
    }
    const int64_t sync_at = pos_ - 4;
    warnings_.push_back("skipped " + std::to_string(sync_at - start) + " corrupt bytes at byte " +
                        std::to_string(start));
    skipped_ += sync_at - start;
    std::fseek(f_, static_cast<long>(sync_at), SEEK_SET);
    pos_ = sync_at;
  }
}

void LogDispatcher::dispatch(const LogEvent& ev) {
  auto it = handlers_.find(ev.channel);
  if (it == handlers_.end()) {
    ++ignored_;
    return;
  }
  it->second(ev);
}

void LogDispatcher::reject(const std::string& channel, const std::string& why) {
  ++rejected_[channel];
  ++rejected_total_;
  last_reason_ = channel + ": " + why;
}

Progress::Progress(std::string tool, double period_s)
    : tool_(std::move(tool)), period_us_(seconds_to_utime(period_s)), next_us_(monotonic_utime() + period_us_) {}

void Progress::update(const LogReader& log, const std::string& what) {
  const int64_t now = monotonic_utime();
  if (now < next_us_) return;
  next_us_ = now + period_us_;
  const double pct = log.file_size() > 0 ? 100.0 * static_cast<double>(log.position()) / log.file_size() : 100.0;
  std::fprintf(stderr, "%s: %.0f%% of %s (%lld events; %s)\n", tool_.c_str(), pct, log.path().c_str(),
               static_cast<long long>(log.events_read()), what.c_str());
}

}  // namespace gpilot
