// GestureCommand: the decision of Alg. 3 as plain data (what GESTURE_CMD carries), shared by decide and flight.
#pragma once

#include <cstdint>

namespace gpilot {

// Values equal gesture_cmd_t::MODE_* (the adapters check this at compile time).
enum class GestureMode : int8_t { Hover = 0, Fine = 1, Up = 2, Down = 3, Closer = 4, Further = 5 };

struct GestureCommand {
  int64_t utime = 0;     //!< capture time of the frame it was decided on, us
  int64_t seq = -1;      //!< that frame's seq
  int32_t track_id = 0;  //!< user it belongs to
  GestureMode mode = GestureMode::Hover;
  // Camera frame (x right, y down, z forward). x, y: mean OUT vector / user box width; z: +1 CLOSER, -1 FURTHER.
  double direction[3] = {0.0, 0.0, 0.0};
  double user_box_width = 0.0;  //!< px, what x, y were divided by
  int n_out = 0;
  int n_front_higher = 0;
  int n_front_lower = 0;
  int buffer_fill = 0;
};

}  // namespace gpilot
