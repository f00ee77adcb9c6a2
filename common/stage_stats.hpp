// Counters behind a process's HEALTH message: accepted, published, rejected (with the last reason),
// dropped, rates and processing-time percentiles per report period, and the process's own failures (a
// handler that threw for a reason other than its input): after the first one the state is ERROR whatever
// the stage sets, until the process restarts. No clock inside: times come in.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gpilot/health_t.hpp"

namespace gpilot {

class StageStats {
 public:
  void accepted() { ++in_; }
  void published() { ++out_; }
  void rejected(const std::string& reason) {
    ++rejected_;
    last_reason_ = reason;
  }
  void dropped() { ++dropped_; }
  void processing_time(int64_t micros);
  void set_state(int8_t state, const std::string& detail) {
    state_ = state;
    detail_ = detail;
  }
  // The process failed (a defect, not a bad input): returns how many times so far.
  int64_t failed(const std::string& what) {
    last_failure_ = what;
    return ++failures_;
  }

  int64_t accepted_count() const { return in_; }
  int64_t published_count() const { return out_; }
  int64_t rejected_count() const { return rejected_; }
  int64_t dropped_count() const { return dropped_; }
  const std::string& last_reject_reason() const { return last_reason_; }
  int64_t failure_count() const { return failures_; }
  // What HEALTH says: ERROR (with the last failure) once the process has failed, unless it is stopping.
  int8_t state() const;
  std::string state_detail() const;

  // The report for the period since the previous one; starts a new period.
  health_t report(int64_t now_utime, const std::string& name, int32_t pid);

 private:
  int64_t in_ = 0, out_ = 0, rejected_ = 0, dropped_ = 0, failures_ = 0;
  int64_t in_at_last_ = 0, out_at_last_ = 0, last_report_utime_ = 0, seq_ = 0;
  std::string last_reason_;
  int8_t state_ = health_t::STATE_STARTING;
  std::string detail_;
  std::string last_failure_;
  std::vector<int64_t> samples_;  // processing times of this period, microseconds
};

// The p-th quantile (0..1) of values, nearest rank; 0 for none. Reorders values.
double quantile(std::vector<int64_t>& values, double p);

}  // namespace gpilot
