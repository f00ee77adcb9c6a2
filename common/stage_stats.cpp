#include "stage_stats.hpp"

#include <algorithm>
#include <cmath>

namespace gpilot {

namespace {
constexpr size_t kMaxSamplesPerPeriod = 100000;  // bounds memory if reports stop; p50/p99 stay meaningful
}

void StageStats::processing_time(int64_t micros) {
  if (samples_.size() < kMaxSamplesPerPeriod) samples_.push_back(micros);
}

double quantile(std::vector<int64_t>& values, double p) {
  if (values.empty()) return 0.0;
  const size_t rank = static_cast<size_t>(std::ceil(p * static_cast<double>(values.size())));
  const size_t k = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return static_cast<double>(values[k]);
}

int8_t StageStats::state() const {
  return failures_ > 0 && state_ != health_t::STATE_STOPPING ? health_t::STATE_ERROR : state_;
}

std::string StageStats::state_detail() const {
  if (failures_ == 0) return detail_;
  return std::to_string(failures_) + (failures_ == 1 ? " failure" : " failures") + " of this process, the last: " +
         last_failure_ + (detail_.empty() ? "" : "; " + detail_);
}

health_t StageStats::report(int64_t now_utime, const std::string& name, int32_t pid) {
  health_t h;
  h.utime = now_utime;
  h.seq = seq_++;
  h.name = name;
  h.pid = pid;
  h.state = state();
  h.state_detail = state_detail();
  h.messages_in = in_;
  h.messages_out = out_;
  h.rejected = rejected_;
  h.dropped = dropped_;
  h.last_reject_reason = last_reason_;
  const double period_s = last_report_utime_ > 0 ? (now_utime - last_report_utime_) * 1e-6 : 0.0;
  h.rate_in_hz = period_s > 0 ? static_cast<float>((in_ - in_at_last_) / period_s) : 0.0f;
  h.rate_out_hz = period_s > 0 ? static_cast<float>((out_ - out_at_last_) / period_s) : 0.0f;
  h.processing_ms_p50 = static_cast<float>(quantile(samples_, 0.50) / 1000.0);
  h.processing_ms_p99 = static_cast<float>(quantile(samples_, 0.99) / 1000.0);
  samples_.clear();
  in_at_last_ = in_;
  out_at_last_ = out_;
  last_report_utime_ = now_utime;
  return h;
}

}  // namespace gpilot
