// DecisionTree: Alg. 3 of the paper, exactly (see PAPER-NOTES "Decision").
#include "decision_tree.hpp"

#include <cmath>

namespace gpilot {

Decision DecisionTree::decide(const StateBuffer& s_out, const StateBuffer& s_front) const {
  Decision d;
  d.n_out = s_out.count_nonzero();
  d.n_front_higher = s_front.count_y_negative();
  d.n_front_lower = s_front.count_y_positive();
  if (d.n_out > params_.out_threshold) {
    Vec2 m = s_out.mean_nonzero();
    if (std::fabs(m.y) > std::fabs(params_.lambda4 * m.x)) {
      m.x = 0.0;
      d.mode = m.y < 0.0 ? GestureMode::Up : GestureMode::Down;
    } else {
      d.mode = GestureMode::Fine;
    }
    d.out_mean = m;
    return d;
  }
  // The paper's order: "higher" is tested first, so a tie above the threshold on both sides (impossible with
  // thresholds >= half the buffer) would come closer.
  if (d.n_front_higher > params_.front_threshold) {
    d.mode = GestureMode::Closer;
    d.z = 1.0;
  } else if (d.n_front_lower > params_.front_threshold) {
    d.mode = GestureMode::Further;
    d.z = -1.0;
  }
  return d;
}

}  // namespace gpilot
