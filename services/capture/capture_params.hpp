// Parameters of gpilot-capture (section `capture`): what is asked of a camera, how frames are published, and
// the synthetic world's camera and data (group `capture.synthetic`).
#pragma once

#include <string>

#include "config.hpp"
#include "synthetic_params.hpp"

namespace gpilot {

struct CaptureParams {
  int width = 640;                    //!< pixels asked of a camera (it may give another size; reported)
  int height = 480;                   //!< pixels
  double fps = 30.0;                  //!< frames per second asked of a camera; pacing of --images
  std::string pixel_format = "BGR8";  //!< published format: BGR8, GRAY8 or JPEG
  int jpeg_quality = 90;              //!< 1..100, with pixel_format JPEG
  double camera_retry_s = 1.0;        //!< wait before reopening a camera that disappeared
  SyntheticParams synthetic;          //!< the default source: the synthetic world

  template <class V>
  void visit(V& v) {
    v("width", width, 16, 7680, "camera width asked for, pixels");
    v("height", height, 16, 4320, "camera height asked for, pixels");
    v("fps", fps, 0.1, 240.0, "camera rate asked for and --images pacing, frames/s");
    v("pixel_format", pixel_format, "published pixel format: BGR8, GRAY8 or JPEG");
    v("jpeg_quality", jpeg_quality, 1, 100, "JPEG quality when pixel_format is JPEG");
    v("camera_retry_s", camera_retry_s, 0.05, 60.0, "wait before reopening a lost camera, s");
    v.group("synthetic", synthetic);
  }
  void check(const ParamCheck& c) const { c.choice("pixel_format", pixel_format, {"BGR8", "GRAY8", "JPEG"}); }
};

}  // namespace gpilot
