#include "face_cascade.hpp"

#include <stdexcept>
#include <string>

#include "paths.hpp"

namespace gpilot {

cv::CascadeClassifier load_face_cascade(const TrackerParams& params) {
  const std::string path = resolve_project_path(params.face.cascade);
  cv::CascadeClassifier cascade;
  if (!cascade.load(path))
    throw std::runtime_error("face cascade '" + path + "' is missing or not a cascade (package opencv-data)");
  return cascade;
}

}  // namespace gpilot
