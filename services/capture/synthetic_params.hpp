// Parameters of the synthetic world (config group `capture.synthetic`): the drone camera's intrinsics and frame rate, and
// the data the person and the scene are made of. The person's pose, place and nuisances come from a scenario.
#pragma once

#include <string>

namespace gpilot {

struct SyntheticParams {
  int width = 640;                 //!< image width, pixels
  int height = 480;                //!< image height, pixels
  double hfov_deg = 60.0;          //!< horizontal field of view (pinhole, square pixels, centred principal point)
  double fps = 25.0;               //!< frames per second of the synthetic camera (the paper's webcam ran at 25)
  double background_distance_m = 20.0;  //!< the background photograph hangs this far from the scenario's camera
  double face_box_m = 0.17;        //!< side of the Haar face box on the person, metres (sets the person's scale)
  std::string face_image = "data/people/astronaut.png";  //!< public-domain portrait whose face is pasted on the head
  std::string skin_tones = "data/skin/synthetic_skin_tones.csv";  //!< real skin colours (UCI) for hands and forearms

  template <class V>
  void visit(V& v) {
    v("width", width, 16, 7680, "synthetic image width, pixels");
    v("height", height, 16, 4320, "synthetic image height, pixels");
    v("hfov_deg", hfov_deg, 5.0, 150.0, "synthetic camera horizontal field of view, degrees");
    v("fps", fps, 0.1, 240.0, "synthetic camera frame rate, frames/s (paper's video 25)");
    v("background_distance_m", background_distance_m, 2.0, 1000.0, "distance of the background photograph, m");
    v("face_box_m", face_box_m, 0.05, 0.5, "Haar face box side on the synthetic person, m");
    v("face_image", face_image, "portrait whose face is pasted on the synthetic head (relative: project root)");
    v("skin_tones", skin_tones, "CSV of real skin colours per tone for hands and forearms (relative: project root)");
  }
};

}  // namespace gpilot
