// What the tracker core needs from files, read by whoever builds the tracker (the service, replay, tools, tests)
// and handed to UserTracker: the core reads no file, as the hands stage's models are loaded by its factory.
#pragma once

#include <memory>

#include <opencv2/objdetect.hpp>

#include "pose/person_detector.hpp"
#include "tracker_params.hpp"

namespace gpilot {

struct TrackerModels {
  cv::CascadeClassifier face_cascade;       //!< tracker.face.cascade
  std::shared_ptr<PersonDetector> persons;  //!< tracker.person's detector; null with the person search off
};

// The face cascade (load_face_cascade) and, with tracker.person.enabled, the person detector's model
// (person.models_dir/pose_detection.onnx). Throws std::runtime_error naming the cascade, PoseModelError naming
// the model file, when one cannot be read.
TrackerModels load_tracker_models(const TrackerParams& params);

}  // namespace gpilot
