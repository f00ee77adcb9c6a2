// The converted models for the pose core's tests: models/pose/*.onnx, made by deploy/setup. A test that needs
// them fails (never skips) when they are missing, saying how to make them.
#pragma once

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "pose/pose_models.hpp"

namespace gpilot::pose_test {

// True when the files of params exist; else a test failure naming them and deploy/setup.
inline bool models_present(const PoseParams& params = PoseParams{}) {
  for (const std::string& path : {pose_detector_path(params), pose_landmark_path(params)})
    if (!std::ifstream(path)) {
      ADD_FAILURE() << path << " is missing: run deploy/setup (it fetches and converts the pose models)";
      return false;
    }
  return true;
}

}  // namespace gpilot::pose_test
