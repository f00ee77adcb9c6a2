// The face search's cascade, read from its file (tracker.face.cascade, resolved as a project path) by whoever
// builds the tracker (the service, replay, tools, tests) and handed to FaceDetector / UserTracker: the core
// reads no file, as the hands stage's models are loaded by its factory and passed in.
#pragma once

#include <opencv2/objdetect.hpp>

#include "tracker_params.hpp"

namespace gpilot {

// Throws std::runtime_error when the file is missing or is not a cascade.
cv::CascadeClassifier load_face_cascade(const TrackerParams& params);

}  // namespace gpilot
