// MediaPipe's OneEuroFilter and LowPassFilter in one class.
#include "one_euro_filter.hpp"

#include <cmath>

#include <opencv2/core/cvdef.h>

#include "clock.hpp"

namespace gpilot {

OneEuroFilter::OneEuroFilter(const OneEuroParams& params, double first_rate_hz)
    : params_(params), first_rate_hz_(first_rate_hz), rate_hz_(first_rate_hz) {}

void OneEuroFilter::reset() {
  rate_hz_ = first_rate_hz_;
  started_ = false;
}

double OneEuroFilter::alpha(double cutoff_hz) const {
  const double tau = 1.0 / (2.0 * CV_PI * cutoff_hz);
  return 1.0 / (1.0 + tau * rate_hz_);
}

double OneEuroFilter::apply(double value, int64_t utime, double value_scale) {
  if (!started_) {
    started_ = true;
    last_utime_ = utime;
    last_raw_ = last_value_ = value;
    last_speed_ = 0.0;
    return value;
  }
  if (utime <= last_utime_) return value;
  rate_hz_ = 1.0 / utime_to_seconds(utime - last_utime_);
  last_utime_ = utime;
  const double speed = (value - last_raw_) * value_scale * rate_hz_;
  const double a_speed = alpha(params_.derivate_cutoff);
  last_speed_ = a_speed * speed + (1.0 - a_speed) * last_speed_;
  const double a = alpha(params_.min_cutoff + params_.beta * std::fabs(last_speed_));
  last_value_ = a * value + (1.0 - a) * last_value_;
  last_raw_ = value;
  return last_value_;
}

}  // namespace gpilot
