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
  // JPEG by default (issue 14): a minute of 640x480 at 25 fps logs in 54-59 MB instead of 1.39 GB. 4:4:4 at
  // quality 65: the far scenario's gestures at 8-10 m (hand squares of ~10 px) are decided as with raw frames
  // (96.5 % of 829 frames; 4:2:0 at quality 80 smeared their skin colour: 66.7 %), and the log stays under
  // 60 MB a minute (quality 70: 63.5 MB on far; quality 60: 85.7 % at 8-10 m).
  std::string pixel_format = "JPEG";  //!< published format: BGR8, GRAY8 or JPEG
  int jpeg_quality = 65;              //!< 1..100, with pixel_format JPEG
  std::string jpeg_chroma = "444";    //!< JPEG chroma subsampling: 444, 422 or 420
  bool jpeg_passthrough = true;       //!< with pixel_format JPEG, an MJPEG video's own JPEG frames are published
                                      //!< as stored (no decode and re-encode; their quality and chroma are the file's)
  double camera_retry_s = 1.0;        //!< wait before reopening a camera that disappeared
  SyntheticParams synthetic;          //!< the default source: the synthetic world

  template <class V>
  void visit(V& v) {
    v("width", width, 16, 7680, "camera width asked for, pixels");
    v("height", height, 16, 4320, "camera height asked for, pixels");
    v("fps", fps, 0.1, 240.0, "camera rate asked for and --images pacing, frames/s");
    v("pixel_format", pixel_format, "published pixel format: BGR8, GRAY8 or JPEG");
    v("jpeg_quality", jpeg_quality, 1, 100, "JPEG quality when pixel_format is JPEG");
    v("jpeg_chroma", jpeg_chroma,
      "JPEG chroma subsampling: 444 (every pixel's colour: small hands far away keep their skin colour), 422 or 420 "
      "(colour per 2x2 pixels: smaller)");
    v("jpeg_passthrough", jpeg_passthrough,
      "with pixel_format JPEG, publish an MJPEG video's own JPEG frames as stored (no decode and re-encode)");
    v("camera_retry_s", camera_retry_s, 0.05, 60.0, "wait before reopening a lost camera, s");
    v.group("synthetic", synthetic);
  }
  void check(const ParamCheck& c) const {
    c.choice("pixel_format", pixel_format, {"BGR8", "GRAY8", "JPEG"});
    c.choice("jpeg_chroma", jpeg_chroma, {"444", "422", "420"});
  }
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
