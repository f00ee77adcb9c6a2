// hands.method pose: the paper's observation read from the user's body landmarks (BlazePose through the pose
// core, seeded by the tracker's box so the body is the user's) instead of skin colour. OUT from p_uc (the
// shoulders' midpoint), FRONT from p_bc (midway between shoulders and hips), NONE at rest or when the arms
// disagree (pose_gesture.hpp). Pure: no LCM, no clock; the same frames, views and utimes give the same output.
#pragma once

#include <cstdint>
#include <string>

#include "hands/hand_method.hpp"
#include "hands/hands_params.hpp"
#include "pose/pose_estimator.hpp"

namespace gpilot {

class PoseHandMethod : public HandMethod {
 public:
  PoseHandMethod(const HandsParams& params, PoseModels models);

  HandsOutput observe(const cv::Mat& bgr, const UserView& user, int64_t utime) override;
  void reset() override;
  std::string description() const override;

  const PoseCounters& counters() const { return pose_.counters(); }

 private:
  HandsParams params_;
  PoseEstimator pose_;
  int32_t track_id_ = -1;
};

}  // namespace gpilot
