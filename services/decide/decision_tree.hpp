// DecisionTree: the paper's Alg. 3, from the two state buffers to a mode and a camera-frame direction.
#pragma once

#include "decide_params.hpp"
#include "gesture_command.hpp"
#include "state_buffer.hpp"

namespace gpilot {

struct Decision {
  GestureMode mode = GestureMode::Hover;
  Vec2 out_mean;   //!< px: mean of the non-zero S_out entries after the lambda4 snap (FINE/UP/DOWN), else 0
  double z = 0.0;  //!< +1 CLOSER (toward the user), -1 FURTHER, else 0
  int n_out = 0;
  int n_front_higher = 0;
  int n_front_lower = 0;
};

class DecisionTree {
 public:
  explicit DecisionTree(const DecideParams& params) : params_(params) {}

  // Alg. 3: n_out > T_out -> mean of the non-zero OUT vectors, x := 0 when |y| > |lambda4 x| (UP/DOWN when
  // snapped, else FINE); else FRONT higher > T_front -> CLOSER, lower > T_front -> FURTHER; else HOVER.
  Decision decide(const StateBuffer& s_out, const StateBuffer& s_front) const;

 private:
  DecideParams params_;
};

}  // namespace gpilot
