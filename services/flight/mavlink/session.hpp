// MavlinkSession: gpilot's side of a MAVLink link, without the socket. Builds the frames we send (HEARTBEAT,
// SET_POSITION_TARGET_LOCAL_NED in MAV_FRAME_BODY_NED, COMMAND_LONG) and turns the autopilot's HEARTBEAT,
// LOCAL_POSITION_NED, ATTITUDE and EXTENDED_SYS_STATE into a VehicleState.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../flight_params.hpp"
#include "../flight_types.hpp"
#include "frame.hpp"
#include "messages.hpp"
#include "signing.hpp"

namespace gpilot::mavlink {

class MavlinkSession {
 public:
  explicit MavlinkSession(const MavlinkParams& params);
  MavlinkSession(const MavlinkSession&) = delete;
  MavlinkSession& operator=(const MavlinkSession&) = delete;

  // MAVLink 2 signing with this 32-byte key: every frame we send is signed on link_id, and only frames with
  // a valid signature and a growing timestamp are read.
  void enable_signing(const std::array<uint8_t, 32>& key, uint8_t link_id);
  bool signing() const { return signer_.has_value(); }
  // The time our signatures carry (they also grow by one per frame): the adapter's clock, given here and
  // with each datagram and setpoint.
  void set_time(int64_t now_utime) { now_ = std::max(now_, now_utime); }

  std::vector<uint8_t> heartbeat();
  // Velocity (body FRD, m/s) and yaw rate only; now_utime sets time_boot_ms (ms since the session's first frame).
  std::vector<uint8_t> setpoint(const Setpoint& sp, int64_t now_utime);
  std::vector<uint8_t> command_long(uint16_t command, const float (&param)[7]);
  std::vector<uint8_t> arm(bool on);
  // ArduPilot reads param7 as metres above home; PX4 as AMSL, so for PX4 param7 is NaN (its MIS_TAKEOFF_ALT).
  std::vector<uint8_t> takeoff(float altitude_m);
  std::vector<uint8_t> land();
  // The mode that follows our setpoints: PX4 OFFBOARD or ArduPilot GUIDED.
  std::vector<uint8_t> engage_mode();
  bool ardupilot() const { return params_.autopilot == "ardupilot"; }
  // PARAM_REQUEST_READ of one parameter by name (the offboard-loss check on ENGAGE: offboard_loss.hpp).
  std::vector<uint8_t> param_request_read(const std::string& name);

  // One received datagram: the latest vehicle state if a LOCAL_POSITION_NED from the target system was in it.
  std::optional<VehicleState> on_datagram(const uint8_t* data, size_t n, int64_t receive_utime);

  const FrameParser& parser() const { return parser_; }
  int64_t other_system() const { return other_system_; }  //!< valid frames from another system id, ignored
  bool heard_autopilot() const { return heard_; }
  std::optional<CommandAck> last_ack() const { return last_ack_; }
  // The PARAM_VALUEs from the autopilot since the last call, oldest first.
  std::vector<ParamValue> take_param_values() { return std::exchange(param_values_, {}); }
  // The autopilot's HEARTBEATs since the last call, oldest first (not a GCS's or a camera's on its system id).
  std::vector<Heartbeat> take_heartbeats() { return std::exchange(heartbeats_, {}); }

 private:
  template <class M>
  std::vector<uint8_t> frame(const M& m);
  uint32_t boot_ms(int64_t now_utime);

  MavlinkParams params_;
  FrameParser parser_;
  std::optional<FrameSigner> signer_;
  std::optional<SignatureChecker> checker_;
  int64_t now_ = 0;
  uint8_t seq_ = 0;
  bool have_boot_ = false;
  int64_t boot_utime_ = 0;
  VehicleState state_;
  int64_t state_seq_ = 0;
  int64_t other_system_ = 0;
  bool heard_ = false;
  std::optional<CommandAck> last_ack_;
  std::vector<ParamValue> param_values_;
  std::vector<Heartbeat> heartbeats_;
};

}  // namespace gpilot::mavlink
