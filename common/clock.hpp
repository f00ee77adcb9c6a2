// Time for adapters and tools. Cores never read a clock: they take `utime` from their inputs, which is
// what makes a replay over a log give the same outputs as the live run.
#pragma once

#include <chrono>
#include <cstdint>
#include <thread>

#include <time.h>

namespace gpilot {

constexpr int64_t kMicrosPerSecond = 1000000;

constexpr int64_t seconds_to_utime(double s) { return static_cast<int64_t>(s * 1e6 + (s >= 0 ? 0.5 : -0.5)); }
constexpr double utime_to_seconds(int64_t us) { return static_cast<double>(us) * 1e-6; }

// Microseconds since the Unix epoch: the time base of every message's utime.
inline int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Microseconds on a clock that never jumps: for measuring durations and pacing.
inline int64_t monotonic_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// CPU time this process has used (user + system, every thread), seconds: what HEALTH reports, so a run's
// summary can say what each process costs per camera frame.
inline double process_cpu_seconds() {
  timespec t{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) != 0) return 0.0;
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Sleeps to fixed ticks of a steady clock; a late tick does not shift the ones after it.
class Pacer {
 public:
  explicit Pacer(double hz) : period_(seconds_to_utime(1.0 / hz)), next_(monotonic_utime()) {}
  void wait() {
    next_ += period_;
    const int64_t now = monotonic_utime();
    if (next_ > now)
      std::this_thread::sleep_for(std::chrono::microseconds(next_ - now));
    else if (now - next_ > 10 * period_)
      next_ = now;  // far behind (a stall): restart the ticks instead of bursting to catch up
  }

 private:
  int64_t period_;
  int64_t next_;
};

}  // namespace gpilot
