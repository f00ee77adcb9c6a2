// Parameters of gpilot-flight (sections `flight`, `sim`, `mavlink`): command scaling, safety, the
// built-in simulator and the MAVLink backend.
#pragma once

#include <string>

#include "config_schema.hpp"
#include "mavlink/endpoint.hpp"

namespace gpilot {

struct FlightParams {
  std::string backend = "sim";        //!< sim (built-in quadrotor), mavlink, or none (LCM only)
  double command_spacing_s = 0.3;     //!< wait between gesture commands (paper 0.6 s): at 0.3 the same false and
                                      //!< confused commands as the paper's on ten closed-loop logs, 0.04-0.08 s
                                      //!< quicker as flown (decide README, gpilot-eval-decide --sweep)
  double stale_timeout_s = 0.25;      //!< command, track or vehicle state older than this: hover (with the
                                      //!< 50 Hz setpoint period, a dead stage gives zero within 0.3 s)
  double setpoint_rate_hz = 50.0;     //!< FLIGHT_SETPOINT (and MAVLink setpoint) rate
  double gain_horizontal = 1.0;       //!< m/s per user-box width of hand offset, sideways
  double gain_vertical = 1.0;         //!< m/s per user-box width of hand offset, up/down
  double speed_along_axis = 0.5;      //!< CLOSER/FURTHER speed, m/s
  double max_horizontal_speed = 1.0;  //!< m/s
  double max_vertical_speed = 0.5;    //!< m/s
  double yaw_gain = 2.0;              //!< rad/s per image width of user-box offset from the image centre
  double yaw_deadband = 0.05;         //!< offsets below this fraction of the image width are ignored
  double max_yaw_rate = 0.8;          //!< rad/s
  double max_command_magnitude = 3.0; //!< |x|, |y| of a command above this many box widths is invalid (hover)
  bool require_vehicle_state = true;  //!< hover without a fresh VEHICLE_STATE (off only for LCM-only dry runs)
  // A height band (above the position origin: the sim's ground, the autopilot's home): no climb above, no
  // descent below. Without a top, a user who keeps an arm up flies the drone until they are out of view.
  double min_height_m = 0.5;
  double max_height_m = 10.0;
  // The camera is fixed to the drone: descending or closing in moves the user's face up and out of the image,
  // climbing moves it down and out; the tracker then follows a body it can no longer check. Those motions
  // are held at zero while the face band (the top face_band_ratio of the user box) touches that edge.
  bool keep_face_in_view = true;
  double face_band_ratio = 0.15;
  // No closing in while the user box is this many image heights tall (about 2.3 m from the user with a 47°
  // vertical field of view). Closer than that the body no longer fits the image, the box's face/neck band
  // no longer covers the neck, and Alg. 2 takes the neck for a hand in front above the centre: CLOSER again,
  // a loop that ends in the user; and seen from the camera 1.5 m up, a hand held high in front of the chest
  // projects onto the body centre (the pose method read it low on 16 of 129 frames below 2.2 m, and FURTHER
  // followed CLOSER when the hand was let go). Ours, not the paper's (its users stood further off); 0: off.
  double closest_box_height_ratio = 0.65;
  // No climbing and no closing in while the user box's point this many box heights below its top (1: the box's
  // bottom, below the hanging hands) is at or below the image's bottom edge. Both move the user down the image
  // (the camera is fixed to the drone), and with the hips and the hanging hands cut BlazePose invents arms: after
  // two UPs a closed-loop tour left the hips 12 px below the frame and a DOWN that followed was not flown (a
  // hanging hand out of view is placed out and down at the edge: cut_hand_margin); held with the hips 25 px above
  // the edge (0.9 of the box), a resting hand half cut by it was read raised: no DOWN and a false command at rest.
  // A hand in front is read against the hips: a tour's CLOSER held only at the hips (0.7) ended at 2.3 m with the
  // box's bottom 30 px below the frame and the hips placed 40 px too high: FURTHER, the way back, was read as a
  // hand at rest, and the UP after it was held. Held, the drone still moves about 0.08 box heights (the
  // setpoint-to-motion lag and the track's). Ours; 0 turns it off.
  double view_box_ratio = 1.0;
  // With MAVLink, the autopilot's own offboard-loss failsafe (PX4 COM_OF_LOSS_T, ArduPilot GUID_TIMEOUT) is what
  // stops the vehicle when this process goes quiet: ENGAGE is refused unless the autopilot reports one no
  // longer than this.
  double max_autopilot_loss_s = 1.0;

  template <class V>
  void visit(V& v) {
    v("backend", backend, "where setpoints go: sim, mavlink or none");
    v("command_spacing_s", command_spacing_s, 0.0, 10.0, "wait between gesture commands, s (paper 0.6; 0.3 measured, decide README)");
    v("stale_timeout_s", stale_timeout_s, 0.01, 10.0, "inputs older than this give a hover setpoint, s");
    v("setpoint_rate_hz", setpoint_rate_hz, 2.0, 500.0, "setpoint rate, Hz (PX4 leaves offboard below 2 Hz)");
    v("gain_horizontal", gain_horizontal, 0.0, 20.0, "sideways speed per box width of hand offset, m/s");
    v("gain_vertical", gain_vertical, 0.0, 20.0, "vertical speed per box width of hand offset, m/s");
    v("speed_along_axis", speed_along_axis, 0.0, 10.0, "CLOSER/FURTHER speed, m/s");
    v("max_horizontal_speed", max_horizontal_speed, 0.0, 20.0, "horizontal speed limit, m/s");
    v("max_vertical_speed", max_vertical_speed, 0.0, 10.0, "vertical speed limit, m/s");
    v("yaw_gain", yaw_gain, 0.0, 20.0, "yaw rate per image width of user offset, rad/s");
    v("yaw_deadband", yaw_deadband, 0.0, 0.5, "user offsets below this fraction of image width: no yaw");
    v("max_yaw_rate", max_yaw_rate, 0.0, 10.0, "yaw rate limit, rad/s");
    v("max_command_magnitude", max_command_magnitude, 0.1, 100.0,
      "command x or y beyond this many box widths is invalid: hover");
    v("require_vehicle_state", require_vehicle_state, "hover unless a fresh vehicle state has been received");
    v("min_height_m", min_height_m, 0.0, 1000.0, "no descent below this height above the origin, m");
    v("max_height_m", max_height_m, 0.0, 1000.0, "no climb above this height above the origin, m");
    v("keep_face_in_view", keep_face_in_view, "no descent/closer with the face at the image top, no climb with it at the bottom");
    v("face_band_ratio", face_band_ratio, 0.0, 1.0, "top fraction of the user box taken as the face band");
    v("closest_box_height_ratio", closest_box_height_ratio, 0.0, 10.0,
      "no closing in while the user box is this many image heights tall (0: no limit)");
    v("view_box_ratio", view_box_ratio, 0.0, 2.0,
      "no climbing, no closing in while the point this many box heights below the user box's top is at the image's bottom (0: no limit)");
    v("max_autopilot_loss_s", max_autopilot_loss_s, 0.0, 60.0,
      "MAVLink: refuse ENGAGE unless the autopilot's offboard-loss failsafe (COM_OF_LOSS_T/GUID_TIMEOUT) is <= this, s");
  }
  void check(const ParamCheck& c) const {
    c.choice("backend", backend, {"sim", "mavlink", "none"});
    // An empty band holds every vertical motion at zero; an inverted one would let the two limits fight.
    c.require(min_height_m < max_height_m, "min_height_m",
              ParamWriter::format_number(min_height_m, false) + " must be below max_height_m " +
                  ParamWriter::format_number(max_height_m, false));
  }
};

struct SimParams {
  double rate_hz = 100.0;             //!< integration rate (the paper's control loop ran at 103 Hz)
  double velocity_time_constant_s = 0.3;  //!< first-order response of velocity to its setpoint
  double yaw_time_constant_s = 0.15;  //!< first-order response of yaw rate to its setpoint
  double start_north = 0.0;           //!< start position, NED metres
  double start_east = 0.0;
  double start_down = -1.5;           //!< 1.5 m above ground
  double start_yaw = 0.0;             //!< rad
  double max_horizontal_speed = 5.0;  //!< m/s, the airframe's limit
  double max_vertical_speed = 3.0;    //!< m/s
  double max_yaw_rate = 3.0;          //!< rad/s
  double land_speed = 0.5;            //!< m/s, descent while landing
  double takeoff_speed = 1.0;         //!< m/s, climb while taking off

  template <class V>
  void visit(V& v) {
    v("rate_hz", rate_hz, 1.0, 2000.0, "simulation step rate, Hz");
    v("velocity_time_constant_s", velocity_time_constant_s, 0.001, 10.0, "velocity response time constant, s");
    v("yaw_time_constant_s", yaw_time_constant_s, 0.001, 10.0, "yaw-rate response time constant, s");
    v("start_north", start_north, -1e4, 1e4, "start position north, m");
    v("start_east", start_east, -1e4, 1e4, "start position east, m");
    v("start_down", start_down, -1e4, 1e4, "start position down, m (negative is up)");
    v("start_yaw", start_yaw, -3.15, 3.15, "start yaw, rad");
    v("max_horizontal_speed", max_horizontal_speed, 0.0, 50.0, "airframe horizontal speed limit, m/s");
    v("max_vertical_speed", max_vertical_speed, 0.0, 20.0, "airframe vertical speed limit, m/s");
    v("max_yaw_rate", max_yaw_rate, 0.0, 20.0, "airframe yaw rate limit, rad/s");
    v("land_speed", land_speed, 0.05, 5.0, "descent speed while landing, m/s");
    v("takeoff_speed", takeoff_speed, 0.05, 5.0, "climb speed while taking off, m/s");
  }
};

struct MavlinkParams {
  // The autopilot: setpoints go there, replies come back to the same socket. PX4 SITL's offboard link listens on
  // 14580 (and answers whoever sent to it); 14540 is where it would send unsolicited.
  std::string endpoint = "udp:127.0.0.1:14580";
  int system_id = 255;                //!< our MAVLink system id (a ground-station-like companion)
  int component_id = 191;             //!< MAV_COMP_ID_ONBOARD_COMPUTER
  int target_system = 1;              //!< the autopilot's system id
  int target_component = 1;           //!< the autopilot's component id
  double heartbeat_hz = 1.0;          //!< our HEARTBEAT rate
  std::string autopilot = "px4";      //!< px4 or ardupilot: which flight mode ENGAGE asks for, how TAKEOFF is sent
  bool set_mode_on_engage = true;     //!< on ENGAGE, ask for PX4 OFFBOARD / ArduPilot GUIDED (MAV_CMD_DO_SET_MODE)
  double param_timeout_s = 1.0;       //!< on ENGAGE, wait this long for the offboard-loss parameter's value
  // Without a message from the autopilot this long the link is lost and gpilot-flight disengages: three of its
  // 1 Hz HEARTBEATs missed (one lost datagram is not a lost link; the setpoint is already zero after
  // flight.stale_timeout_s without its position).
  double link_timeout_s = 3.0;
  std::string signing_key;            //!< MAVLink 2 signing key file (32 bytes, as gpilot-keygen makes); "" = unsigned
  int signing_link_id = 1;            //!< our link id in signatures

  template <class V>
  void visit(V& v) {
    v("endpoint", endpoint, "autopilot endpoint, udp:HOST:PORT");
    v("system_id", system_id, 1, 255, "our MAVLink system id");
    v("component_id", component_id, 0, 255, "our MAVLink component id");
    v("target_system", target_system, 0, 255, "autopilot system id");
    v("target_component", target_component, 0, 255, "autopilot component id");
    v("heartbeat_hz", heartbeat_hz, 0.2, 10.0, "HEARTBEAT rate, Hz");
    v("autopilot", autopilot, "px4 or ardupilot (flight mode asked on ENGAGE, TAKEOFF altitude convention)");
    v("set_mode_on_engage", set_mode_on_engage, "on ENGAGE send DO_SET_MODE: PX4 OFFBOARD or ArduPilot GUIDED");
    v("param_timeout_s", param_timeout_s, 0.05, 30.0,
      "on ENGAGE, wait this long for the autopilot's offboard-loss parameter (else refuse), s");
    v("link_timeout_s", link_timeout_s, 0.5, 60.0,
      "nothing from the autopilot this long: its link is lost, disengage (re-ENGAGE once it is back), s");
    v("signing_key", signing_key,
      "MAVLink 2 signing key file (32 bytes or 64 hex digits, mode 0600; gpilot-keygen makes one): every frame sent "
      "is signed, only validly signed frames are read. \"\" = unsigned (HEALTH says so)");
    v("signing_link_id", signing_link_id, 0, 255, "our link id in MAVLink 2 signatures");
  }
  void check(const ParamCheck& c) const {
    c.choice("autopilot", autopilot, {"px4", "ardupilot"});
    try {
      (void)mavlink::parse_endpoint(endpoint);
    } catch (const std::invalid_argument& e) {
      c.require(false, "endpoint", e.what());
    }
  }
};

// Flight's sections of the config file: the bridge, the built-in simulator and the MAVLink backend
// (services/system assembles the whole file from every stage's).
inline void add_flight_sections(ConfigSchema& schema) {
  schema.section<FlightParams>("flight").section<SimParams>("sim").section<MavlinkParams>("mavlink");
}

}  // namespace gpilot
