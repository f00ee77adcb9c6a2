// The MAVLink common-set messages gpilot uses, each with its id, CRC_EXTRA, payload length and wire order.
// Fields are in wire order (largest type first, then extensions), as the MAVLink XML generator sorts them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gpilot::mavlink {

struct MessageInfo {
  uint32_t id;
  const char* name;
  uint8_t crc_extra;
  uint8_t length;  //!< full payload length including extensions (frames may be shorter: trailing zeros cut)
};

// The table entry for an id, or nullptr when gpilot does not know the message.
const MessageInfo* message_info(uint32_t id);

struct Heartbeat {  // id 0
  static constexpr uint32_t kId = 0;
  uint32_t custom_mode = 0;
  uint8_t type = 0;             //!< MAV_TYPE
  uint8_t autopilot = 0;        //!< MAV_AUTOPILOT
  uint8_t base_mode = 0;        //!< MAV_MODE_FLAG bits (128 = armed)
  uint8_t system_status = 0;    //!< MAV_STATE
  uint8_t mavlink_version = 3;
};

struct Attitude {  // id 30
  static constexpr uint32_t kId = 30;
  uint32_t time_boot_ms = 0;
  float roll = 0, pitch = 0, yaw = 0;                 //!< rad
  float rollspeed = 0, pitchspeed = 0, yawspeed = 0;  //!< rad/s
};

struct LocalPositionNed {  // id 32
  static constexpr uint32_t kId = 32;
  uint32_t time_boot_ms = 0;
  float x = 0, y = 0, z = 0;     //!< m, local NED
  float vx = 0, vy = 0, vz = 0;  //!< m/s
};

struct CommandLong {  // id 76
  static constexpr uint32_t kId = 76;
  float param[7] = {0, 0, 0, 0, 0, 0, 0};
  uint16_t command = 0;  //!< MAV_CMD
  uint8_t target_system = 0;
  uint8_t target_component = 0;
  uint8_t confirmation = 0;
};

struct CommandAck {  // id 77
  static constexpr uint32_t kId = 77;
  uint16_t command = 0;
  uint8_t result = 0;  //!< MAV_RESULT
  uint8_t progress = 0;
  int32_t result_param2 = 0;
  uint8_t target_system = 0;
  uint8_t target_component = 0;
};

struct SetPositionTargetLocalNed {  // id 84
  static constexpr uint32_t kId = 84;
  uint32_t time_boot_ms = 0;
  float x = 0, y = 0, z = 0;
  float vx = 0, vy = 0, vz = 0;
  float afx = 0, afy = 0, afz = 0;
  float yaw = 0, yaw_rate = 0;
  uint16_t type_mask = 0;  //!< POSITION_TARGET_TYPEMASK: set bits are ignored
  uint8_t target_system = 0;
  uint8_t target_component = 0;
  uint8_t coordinate_frame = 0;  //!< MAV_FRAME
};

struct ExtendedSysState {  // id 245
  static constexpr uint32_t kId = 245;
  uint8_t vtol_state = 0;
  uint8_t landed_state = 0;  //!< MAV_LANDED_STATE (same values as vehicle_state_t::LANDED_*)
};

struct ParamRequestRead {  // id 20
  static constexpr uint32_t kId = 20;
  int16_t param_index = -1;  //!< -1: look the parameter up by param_id
  uint8_t target_system = 0;
  uint8_t target_component = 0;
  char param_id[16] = {};    //!< not NUL-terminated when 16 characters long
};

struct ParamValue {  // id 22
  static constexpr uint32_t kId = 22;
  float param_value = 0;
  uint16_t param_count = 0;
  uint16_t param_index = 0;
  char param_id[16] = {};
  uint8_t param_type = 0;  //!< MAV_PARAM_TYPE (9: REAL32)
};

// Payload bytes of a message, full length (the frame encoder cuts trailing zeros).
std::vector<uint8_t> pack(const Heartbeat& m);
std::vector<uint8_t> pack(const Attitude& m);
std::vector<uint8_t> pack(const LocalPositionNed& m);
std::vector<uint8_t> pack(const CommandLong& m);
std::vector<uint8_t> pack(const CommandAck& m);
std::vector<uint8_t> pack(const SetPositionTargetLocalNed& m);
std::vector<uint8_t> pack(const ExtendedSysState& m);
std::vector<uint8_t> pack(const ParamRequestRead& m);
std::vector<uint8_t> pack(const ParamValue& m);

// From a payload of any length up to the full one (missing bytes read as zeros).
Heartbeat unpack_heartbeat(const std::vector<uint8_t>& p);
Attitude unpack_attitude(const std::vector<uint8_t>& p);
LocalPositionNed unpack_local_position_ned(const std::vector<uint8_t>& p);
CommandLong unpack_command_long(const std::vector<uint8_t>& p);
CommandAck unpack_command_ack(const std::vector<uint8_t>& p);
SetPositionTargetLocalNed unpack_set_position_target_local_ned(const std::vector<uint8_t>& p);
ExtendedSysState unpack_extended_sys_state(const std::vector<uint8_t>& p);
ParamRequestRead unpack_param_request_read(const std::vector<uint8_t>& p);
ParamValue unpack_param_value(const std::vector<uint8_t>& p);
// A param_id as text (up to its first NUL, at most 16 characters).
std::string param_name(const char (&id)[16]);

// The constants gpilot uses (from the MAVLink common set).
constexpr uint8_t kMavTypeOnboardController = 18;
constexpr uint8_t kMavAutopilotInvalid = 8;
constexpr uint8_t kMavStateActive = 4;
constexpr uint8_t kMavModeFlagSafetyArmed = 128;
constexpr uint8_t kMavModeFlagCustomModeEnabled = 1;
constexpr uint8_t kMavFrameBodyNed = 8;
constexpr uint16_t kMavCmdNavLand = 21;
constexpr uint16_t kMavCmdNavTakeoff = 22;
constexpr uint16_t kMavCmdDoSetMode = 176;
constexpr uint16_t kMavCmdComponentArmDisarm = 400;
constexpr uint8_t kPx4CustomMainModeOffboard = 6;
constexpr uint8_t kArduCopterModeGuided = 4;
constexpr uint8_t kMavParamTypeReal32 = 9;
// Velocity and yaw rate only: ignore position (1|2|4), acceleration (64|128|256) and yaw (1024).
constexpr uint16_t kTypeMaskVelocityYawRate = 1 | 2 | 4 | 64 | 128 | 256 | 1024;

}  // namespace gpilot::mavlink
