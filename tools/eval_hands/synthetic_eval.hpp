// gpilot-eval-hands --scenario: the hands stage (make_hand_method, the TRUE user box, no face, track 1) over a
// synthetic scenario, scored against the synthetic world's ground truth: kind accuracy (NONE/OUT/FRONT) with a
// confusion matrix, angle and length error of OUT vectors, higher/lower success of FRONT frames; a few
// annotated PNGs. The tracker is not involved.
#pragma once

#include <cstdint>
#include <string>

#include "config.hpp"

namespace gpilot {

struct SyntheticEvalOptions {
  std::string scenario = "tour";  //!< deploy/scenarios/NAME.yaml or a path
  uint64_t seed = 1;
  int stride = 1;                 //!< every N-th frame
  std::string png_dir = "eval_hands_png";  //!< "" = none
  int pngs = 6;
  std::string csv_path;           //!< "" = none
  bool json = false;
};

// Prints the table (or one JSON object) on stdout; returns the exit status.
int run_synthetic_eval(const SyntheticEvalOptions& options, const Config& config);

}  // namespace gpilot
