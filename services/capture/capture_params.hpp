// Parameters of gpilot-capture (section `capture`): what is asked of a camera, how frames are published, and
// the synthetic world's camera and data (group `capture.synthetic`).
#pragma once

#include <string>

#include "config_schema.hpp"
#include "image_codec_params.hpp"
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

// Capture's section of the config file, and its rule on the image section: every frame consumer refuses a
// frame larger than image.max_*, so frames capture makes larger would feed nobody.
inline void add_capture_sections(ConfigSchema& schema) {
  schema.section<CaptureParams>("capture").rule([](const Config& config) {
    const auto image = config.section<ImageLimits>("image");
    const auto capture = config.section<CaptureParams>("capture");
    const ParamCheck c("image");
    const auto fits = [&](const char* key, int limit, const char* source, int size) {
      c.require(size <= limit, key,
                std::to_string(limit) + " is below " + source + " " + std::to_string(size) +
                    " (every stage would refuse its frames)");
    };
    fits("max_width", image.max_width, "capture.width", capture.width);
    fits("max_height", image.max_height, "capture.height", capture.height);
    fits("max_width", image.max_width, "capture.synthetic.width", capture.synthetic.width);
    fits("max_height", image.max_height, "capture.synthetic.height", capture.synthetic.height);
  });
}

}  // namespace gpilot
