// gpilot-flight: the only process that moves the vehicle. Reads GESTURE_CMD, USER_TRACK, FLIGHT_CONTROL (and
// VEHICLE_STATE from the bus with backend none); writes FLIGHT_SETPOINT at flight.setpoint_rate_hz always
// (zero with reasons when unsafe), VEHICLE_STATE from the built-in simulator (backend sim) or the autopilot
// (backend mavlink, MAVLink v2 over UDP), and HEALTH.
#include <cmath>
#include <memory>
#include <optional>

#include "bus_node.hpp"
#include "flight_bridge.hpp"
#include "mavlink/session.hpp"
#include "mavlink/udp_link.hpp"
#include "quadrotor_sim.hpp"
#include "service_cli.hpp"

namespace gpilot {
namespace {

static_assert(reason::kNotEngaged == flight_setpoint_t::REASON_NOT_ENGAGED &&
                  reason::kStartup == flight_setpoint_t::REASON_STARTUP &&
                  reason::kStaleCommand == flight_setpoint_t::REASON_STALE_COMMAND &&
                  reason::kStaleTrack == flight_setpoint_t::REASON_STALE_TRACK &&
                  reason::kStaleVehicle == flight_setpoint_t::REASON_STALE_VEHICLE &&
                  reason::kTrackLost == flight_setpoint_t::REASON_TRACK_LOST &&
                  reason::kInvalidInput == flight_setpoint_t::REASON_INVALID_INPUT &&
                  reason::kCommandDelay == flight_setpoint_t::REASON_COMMAND_DELAY &&
                  reason::kClipped == flight_setpoint_t::REASON_CLIPPED &&
                  reason::kLanding == flight_setpoint_t::REASON_LANDING &&
                  reason::kHeightLimit == flight_setpoint_t::REASON_HEIGHT_LIMIT,
              "reason bits and flight_setpoint_t::REASON_* must agree");
static_assert(static_cast<int>(VehicleState::Landed::Landing) == vehicle_state_t::LANDED_LANDING &&
                  static_cast<int>(VehicleState::Landed::InAir) == vehicle_state_t::LANDED_IN_AIR,
              "VehicleState::Landed and vehicle_state_t::LANDED_* must agree");

GestureCommand to_core(const gesture_cmd_t& m) {
  GestureCommand c;
  c.utime = m.utime;
  c.seq = m.seq;
  c.track_id = m.track_id;
  c.mode = static_cast<GestureMode>(m.mode);
  for (int i = 0; i < 3; ++i) c.direction[i] = m.direction[i];
  c.user_box_width = m.user_box_width;
  return c;
}

UserTrack to_core(const user_track_t& m) {
  UserTrack t;
  t.utime = m.utime;
  t.tracking = m.status == user_track_t::STATUS_TRACKING;
  for (int i = 0; i < 4; ++i) t.box[i] = m.box[i];
  t.track_id = m.track_id;
  t.image_width = m.image_width;
  return t;
}

VehicleState to_core(const vehicle_state_t& m) {
  VehicleState v;
  v.utime = m.utime;
  v.seq = m.seq;
  for (int i = 0; i < 3; ++i) {
    v.position[i] = m.position[i];
    v.velocity[i] = m.velocity[i];
    v.attitude[i] = m.attitude[i];
  }
  v.yaw_rate = m.yaw_rate;
  v.armed = m.armed;
  v.landed = static_cast<VehicleState::Landed>(m.landed_state);
  return v;
}

vehicle_state_t to_message(const VehicleState& v, int8_t source) {
  vehicle_state_t m{};
  m.utime = v.utime;
  m.seq = v.seq;
  for (int i = 0; i < 3; ++i) {
    m.position[i] = static_cast<float>(v.position[i]);
    m.velocity[i] = static_cast<float>(v.velocity[i]);
    m.attitude[i] = static_cast<float>(v.attitude[i]);
  }
  m.yaw_rate = static_cast<float>(v.yaw_rate);
  m.armed = v.armed;
  m.source = source;
  m.landed_state = static_cast<int8_t>(v.landed);
  return m;
}

flight_setpoint_t to_message(const Setpoint& s) {
  flight_setpoint_t m{};
  m.utime = s.utime;
  m.seq = s.seq;
  for (int i = 0; i < 3; ++i) m.velocity[i] = static_cast<float>(s.velocity[i]);
  m.yaw_rate = static_cast<float>(s.yaw_rate);
  m.engaged = s.engaged;
  m.mode = s.mode;
  m.reasons = s.reasons;
  return m;
}

// The flight service: holds the latest inputs, ticks the bridge, drives the chosen backend.
class FlightService {
 public:
  FlightService(const Config& config, BusNode& node)
      : node_(node),
        fp_(config.section<FlightParams>("flight")),
        sim_params_(config.section<SimParams>("sim")),
        mav_params_(config.section<MavlinkParams>("mavlink")),
        bridge_(fp_) {
    if (fp_.backend == "sim") {
      sim_.emplace(sim_params_);
    } else if (fp_.backend == "mavlink") {
      try {
        link_ = std::make_unique<mavlink::UdpLink>(mavlink::parse_endpoint(mav_params_.endpoint));
      } catch (const std::invalid_argument& e) {
        throw ConfigError(std::string("mavlink.endpoint: ") + e.what());
      }
      if (mav_params_.autopilot != "px4" && mav_params_.autopilot != "ardupilot")
        throw ConfigError("mavlink.autopilot: '" + mav_params_.autopilot + "' is not one of px4, ardupilot");
      session_.emplace(mav_params_);
    } else if (fp_.backend != "none") {
      throw ConfigError("flight.backend: '" + fp_.backend + "' is not one of sim, mavlink, none");
    }
  }

  void start() {
    node_.subscribe<gesture_cmd_t>("GESTURE_CMD", [this](const gesture_cmd_t& m, int64_t) {
      in_.command = to_core(m);
      in_.command_received = wall_utime();
    });
    node_.subscribe<user_track_t>("USER_TRACK", [this](const user_track_t& m, int64_t) {
      in_.track = to_core(m);
      in_.track_received = wall_utime();
    });
    node_.subscribe<flight_control_t>("FLIGHT_CONTROL", [this](const flight_control_t& m, int64_t) { control(m); });
    if (fp_.backend == "none") {
      node_.subscribe<vehicle_state_t>("VEHICLE_STATE", [this](const vehicle_state_t& m, int64_t) {
        in_.vehicle = to_core(m);
        in_.vehicle_received = wall_utime();
      });
    }
    node_.every(1.0 / fp_.setpoint_rate_hz, [this] { tick(); });
    if (sim_) node_.every(1.0 / sim_params_.rate_hz, [this] { step_sim(); });
    if (session_) {
      node_.every(1.0 / mav_params_.heartbeat_hz, [this] { link_->send(session_->heartbeat()); });
      node_.every(0.002, [this] { poll_mavlink(); });
      node_.every(1.0, [this] { report_link(); });
      link_->send(session_->heartbeat());
    }
    node_.set_state(health_t::STATE_OK, "backend " + fp_.backend + ", not engaged");
  }

 private:
  void control(const flight_control_t& m) {
    // gpilot-ctl repeats each request against multicast loss: act on it once.
    if (m.utime == last_control_utime_ && m.seq == last_control_seq_ && m.source == last_control_source_) return;
    last_control_utime_ = m.utime;
    last_control_seq_ = m.seq;
    last_control_source_ = m.source;
    switch (m.command) {
      case flight_control_t::COMMAND_ENGAGE:
        in_.engaged = true;
        in_.landing = false;
        setpoints_since_engage_ = 0;
        break;
      case flight_control_t::COMMAND_DISENGAGE: in_.engaged = false; break;
      case flight_control_t::COMMAND_LAND:
        in_.engaged = false;
        in_.landing = true;
        if (sim_) sim_->land();
        if (session_) link_->send(session_->land());
        break;
      case flight_control_t::COMMAND_ARM:
        if (sim_) sim_->arm();
        if (session_) link_->send(session_->arm(true));
        break;
      case flight_control_t::COMMAND_DISARM:
        if (sim_) sim_->disarm();
        if (session_) link_->send(session_->arm(false));
        break;
      case flight_control_t::COMMAND_TAKEOFF:
        if (!(m.takeoff_altitude > 0.0f)) {
          node_.reject("FLIGHT_CONTROL: TAKEOFF needs a positive takeoff_altitude");
          return;
        }
        in_.landing = false;
        if (sim_) sim_->takeoff(m.takeoff_altitude);
        if (session_) link_->send(session_->takeoff(m.takeoff_altitude));
        break;
      default: break;
    }
    node_.set_state(health_t::STATE_OK, "backend " + fp_.backend + (in_.engaged ? ", ENGAGED" : ", not engaged") +
                                            (in_.landing ? ", landing" : "") + " (last request from " + m.source + ")");
  }

  void tick() {
    in_.now = wall_utime();
    last_ = bridge_.update(in_);
    node_.publish("FLIGHT_SETPOINT", to_message(last_));
    if (session_ && in_.engaged) {
      link_->send(session_->setpoint(last_, in_.now));
      // PX4 accepts OFFBOARD only once setpoints are streaming: ask after a short run of them.
      if (++setpoints_since_engage_ == 10 && mav_params_.set_mode_on_engage) link_->send(session_->engage_mode());
    }
  }

  void step_sim() {
    const int64_t now = wall_utime();
    sim_->step(last_, 1.0 / sim_params_.rate_hz);
    in_.vehicle = sim_->state(now);
    in_.vehicle_received = now;
    node_.publish("VEHICLE_STATE", to_message(*in_.vehicle, vehicle_state_t::SOURCE_SIMULATOR));
  }

  void poll_mavlink() {
    std::vector<uint8_t> buf;
    while (link_->receive(buf)) {
      const int64_t now = wall_utime();
      const int64_t rejected_before = session_->parser().rejected();
      const auto state = session_->on_datagram(buf.data(), buf.size(), now);
      for (int64_t i = rejected_before; i < session_->parser().rejected(); ++i)
        node_.reject(std::string("MAVLink: ") + session_->parser().last_reject());
      if (state) {
        in_.vehicle = *state;
        in_.vehicle_received = now;
        node_.publish("VEHICLE_STATE", to_message(*state, vehicle_state_t::SOURCE_MAVLINK));
      }
    }
  }

  void report_link() {
    const int64_t now = wall_utime();
    if (!session_->heard_autopilot())
      node_.set_state(health_t::STATE_DEGRADED, "no autopilot HEARTBEAT from " + mav_params_.endpoint);
    else if (!in_.vehicle || now - in_.vehicle_received > kMicrosPerSecond)
      node_.set_state(health_t::STATE_DEGRADED, "no LOCAL_POSITION_NED from " + mav_params_.endpoint + " for 1 s");
    else
      node_.set_state(health_t::STATE_OK, "autopilot at " + mav_params_.endpoint + (in_.engaged ? ", ENGAGED" : ""));
  }

  BusNode& node_;
  FlightParams fp_;
  SimParams sim_params_;
  MavlinkParams mav_params_;
  FlightBridge bridge_;
  BridgeInputs in_;
  Setpoint last_;
  std::optional<QuadrotorSim> sim_;
  std::unique_ptr<mavlink::UdpLink> link_;
  std::optional<mavlink::MavlinkSession> session_;
  int setpoints_since_engage_ = 0;
  int64_t last_control_utime_ = -1;
  int64_t last_control_seq_ = -1;
  std::string last_control_source_;
};

}  // namespace
}  // namespace gpilot

int main(int argc, char** argv) {
  using namespace gpilot;
  ServiceCli cli("gpilot-flight",
                 "gpilot-flight: turns GESTURE_CMD into a body-frame velocity setpoint (speed from the hand's offset\n"
                 "in user-box widths, yaw to keep the user centred, the paper's 600 ms command spacing) and hovers\n"
                 "unless ENGAGED with fresh, valid inputs and a tracked user. Backends (flight.backend): sim (built-in\n"
                 "quadrotor, publishes VEHICLE_STATE), mavlink (MAVLink v2 over UDP, mavlink.endpoint), none.\n"
                 "Reads GESTURE_CMD, USER_TRACK, FLIGHT_CONTROL (+ VEHICLE_STATE with backend none); writes\n"
                 "FLIGHT_SETPOINT, VEHICLE_STATE, HEALTH. Config sections: flight, sim, mavlink.");
  return cli.run_node(argc, argv, [](const Config& config, BusNode& node) {
    FlightService service(config, node);
    service.start();
    node.run();
    return 0;
  });
}
