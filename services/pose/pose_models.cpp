// Loads the nets, finds their outputs by size with one forward pass on a blank input, and refuses what does
// not match.
#include "pose_models.hpp"

#include <fstream>

#include "depthwise_conv.hpp"
#include "paths.hpp"

namespace gpilot {
namespace {

PoseNet read_net(const std::string& path, const char* what) {
  if (!std::ifstream(path, std::ios::binary))
    throw PoseModelError(path + ": cannot open the " + what + " model (run deploy/setup to fetch and convert the models)");
  PoseNet n;
  n.path = path;
  try {
    n.net = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw PoseModelError(path + ": not a readable ONNX " + what + " model (truncated or damaged?): " + e.what());
  }
  if (n.net.empty()) throw PoseModelError(path + ": the " + what + " model is empty");
  n.net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  n.net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  return n;
}

// Runs the net once on a blank input of the given side and picks, for each wanted element count, the output
// that has it.
void find_outputs(PoseNet& n, const char* what, int side, std::initializer_list<std::pair<size_t, const char*>> wanted) {
  const std::vector<std::string> names = n.net.getUnconnectedOutLayersNames();
  std::vector<cv::Mat> outs;
  try {
    n.net.setInput(cv::Mat(std::vector<int>{1, 3, side, side}, CV_32F, cv::Scalar(0)));
    n.net.forward(outs, names);
  } catch (const cv::Exception& e) {
    throw PoseModelError(n.path + ": the " + what + " model does not run on a 1x3x" + std::to_string(side) + "x" +
                         std::to_string(side) + " input: " + e.what());
  }
  std::string found;
  for (size_t i = 0; i < outs.size(); ++i) found += (i ? ", " : "") + names[i] + " (" + std::to_string(outs[i].total()) + ")";
  for (const auto& [count, role] : wanted) {
    size_t match = outs.size();
    for (size_t i = 0; i < outs.size(); ++i)
      if (outs[i].total() == count) match = i;
    if (match == outs.size())
      throw PoseModelError(n.path + ": the " + what + " model has no " + role + " output of " + std::to_string(count) +
                           " values; its outputs: " + found);
    n.outputs.push_back(names[match]);
  }
}

}  // namespace

std::string pose_detector_path(const PoseParams& params) {
  return resolve_project_path(params.models_dir + "/pose_detection.onnx");
}

std::string pose_landmark_path(const PoseParams& params) {
  return resolve_project_path(params.models_dir + "/pose_landmark_" + params.model + ".onnx");
}

PoseModels PoseModels::load(const PoseParams& params) {
  return load(pose_detector_path(params), pose_landmark_path(params), params.fast_depthwise);
}

// cv::dnn makes a net's layers at its first forward, which find_outputs runs: in the DepthwiseConvScope.
PoseNet PoseModels::load_detector(const std::string& detector_path, bool fast_depthwise) {
  const DepthwiseConvScope depthwise(fast_depthwise);
  PoseNet n = read_net(detector_path, "person detector");
  find_outputs(n, "person detector", kDetectorInputSize,
               {{size_t{kDetectorAnchors} * kDetectorBoxValues, "box"}, {size_t{kDetectorAnchors}, "score"}});
  return n;
}

PoseModels PoseModels::load(const std::string& detector_path, const std::string& landmark_path, bool fast_depthwise) {
  PoseModels m;
  m.detector = load_detector(detector_path, fast_depthwise);
  const DepthwiseConvScope depthwise(fast_depthwise);
  m.landmark = read_net(landmark_path, "pose landmark");
  find_outputs(m.landmark, "pose landmark", kLandmarkInputSize,
               {{size_t{kLandmarkPoints} * kLandmarkValues, "landmark"}, {size_t{1}, "pose flag"}});
  return m;
}

}  // namespace gpilot
