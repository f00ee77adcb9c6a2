// The One Euro filter (Casiry, Roussel, Vogel, CHI 2012) as MediaPipe's OneEuroFilter runs it: an exponential
// low-pass whose cutoff rises with the (low-passed) speed, cutoff = min_cutoff + beta |speed|, the rate taken
// from the times given (no clock). The speed is multiplied by value_scale (MediaPipe: 1 / object size).
#pragma once

#include <cstdint>

#include "pose_params.hpp"

namespace gpilot {

class OneEuroFilter {
 public:
  // first_rate_hz: the rate assumed for the second value, before two times give it.
  OneEuroFilter(const OneEuroParams& params, double first_rate_hz);

  // The filtered value at utime (microseconds). A utime not after the last one returns value unfiltered and
  // changes nothing (MediaPipe's behaviour).
  double apply(double value, int64_t utime, double value_scale);
  void reset();

 private:
  double alpha(double cutoff_hz) const;

  OneEuroParams params_;
  double first_rate_hz_;
  double rate_hz_;
  bool started_ = false;
  int64_t last_utime_ = 0;
  double last_raw_ = 0.0;
  double last_value_ = 0.0;
  double last_speed_ = 0.0;
};

}  // namespace gpilot
