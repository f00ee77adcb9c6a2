// Parameters of the image decoding every frame consumer shares (section `image`): the largest frame a stage
// takes. A frame's size is checked against them before any pixel is decoded (a JPEG's from its SOF header),
// so a small datagram that claims a huge image costs no decoding time and no memory.
#pragma once

namespace gpilot {

struct ImageLimits {
  int max_width = 1920;   //!< pixels
  int max_height = 1080;  //!< pixels

  template <class V>
  void visit(V& v) {
    v("max_width", max_width, 16, 16384, "largest frame width taken, pixels (at least capture.width)");
    v("max_height", max_height, 16, 16384, "largest frame height taken, pixels (at least capture.height)");
  }
};

}  // namespace gpilot
