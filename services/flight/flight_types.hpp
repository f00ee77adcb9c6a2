// Plain data the flight cores exchange: the user track, the vehicle state, a body-frame setpoint and its reasons.
#pragma once

#include <cstdint>

namespace gpilot {

struct UserTrack {
  int64_t utime = 0;
  bool tracking = false;               //!< status TRACKING (SEARCHING and LOST are not flown on)
  double box[4] = {0.0, 0.0, 0.0, 0.0};  //!< x, y, width, height, px
  int32_t track_id = 0;
  int32_t image_width = 0;             //!< px
  int32_t image_height = 0;            //!< px (0: unknown, the view rules are not applied)
};

struct VehicleState {
  int64_t utime = 0;
  int64_t seq = 0;
  double position[3] = {0.0, 0.0, 0.0};  //!< world NED, m
  double velocity[3] = {0.0, 0.0, 0.0};  //!< world NED, m/s
  double attitude[3] = {0.0, 0.0, 0.0};  //!< roll, pitch, yaw, rad (yaw 0 north, positive clockwise from above)
  double yaw_rate = 0.0;                 //!< rad/s
  bool armed = false;
  enum class Landed : int8_t { Unknown = 0, OnGround = 1, InAir = 2, Takeoff = 3, Landing = 4 };  // = LANDED_*
  Landed landed = Landed::Unknown;
};

// Values equal flight_setpoint_t::REASON_* (the adapter checks this at compile time).
namespace reason {
constexpr int32_t kNotEngaged = 1;
constexpr int32_t kStartup = 2;
constexpr int32_t kStaleCommand = 4;
constexpr int32_t kStaleTrack = 8;
constexpr int32_t kStaleVehicle = 16;
constexpr int32_t kTrackLost = 32;
constexpr int32_t kInvalidInput = 64;
constexpr int32_t kCommandDelay = 128;
constexpr int32_t kClipped = 256;
constexpr int32_t kLanding = 512;
constexpr int32_t kHeightLimit = 1024;
constexpr int32_t kViewLimit = 2048;
constexpr int32_t kRangeLimit = 4096;
}  // namespace reason

struct Setpoint {
  int64_t utime = 0;
  int64_t seq = -1;                      //!< seq of the frame whose command is flown; -1 if none
  double velocity[3] = {0.0, 0.0, 0.0};  //!< body FRD, m/s
  double yaw_rate = 0.0;                 //!< rad/s, positive turns right (clockwise from above)
  bool engaged = false;
  int8_t mode = 0;                       //!< GestureMode being flown (Hover when zeroed)
  int32_t reasons = 0;                   //!< reason::* bits
  int64_t latest_command_seq = -1;       //!< the newest command the bridge had (-1 none)
  int64_t track_utime = 0;               //!< the newest track's utime (0 none)
  bool is_zero() const { return velocity[0] == 0.0 && velocity[1] == 0.0 && velocity[2] == 0.0 && yaw_rate == 0.0; }
};

}  // namespace gpilot
