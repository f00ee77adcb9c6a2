#include "tracker_models.hpp"

#include "face_cascade.hpp"
#include "pose/pose_models.hpp"

namespace gpilot {

TrackerModels load_tracker_models(const TrackerParams& params) {
  TrackerModels m;
  m.face_cascade = load_face_cascade(params);
  if (params.person.enabled) {
    PoseParams pose;
    pose.models_dir = params.person.models_dir;
    pose.detector_score_threshold = params.person.score_threshold;
    m.persons = std::make_shared<PersonDetector>(pose, PoseModels::load_detector(pose_detector_path(pose)));
  }
  return m;
}

}  // namespace gpilot
