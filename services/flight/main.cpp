// gpilot-flight: the only process that moves the vehicle. Reads GESTURE_CMD, USER_TRACK, FLIGHT_CONTROL (and
// VEHICLE_STATE from the bus with backend none); writes FLIGHT_SETPOINT at flight.setpoint_rate_hz always
// (zero with reasons when unsafe), VEHICLE_STATE from the built-in simulator (backend sim) or the autopilot
// (backend mavlink, MAVLink v2 over UDP), and HEALTH.
// Watched: READY=1 once running and WATCHDOG=1 from the loop that publishes the setpoints (sd_notify; systemd's
// WatchdogSec or gpilot-launch's watchdog_s), so a frozen loop is a silent watchdog: killed and restarted.
// With MAVLink, ENGAGE first reads the autopilot's offboard-loss failsafe time (mavlink/offboard_loss.hpp).
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "bus_node.hpp"
#include "flight_bridge.hpp"
#include "flight_messages.hpp"
#include "mavlink/offboard_loss.hpp"
#include "bus_key.hpp"
#include "log.hpp"
#include "mavlink/session.hpp"
#include "mavlink/udp_link.hpp"
#include "quadrotor_sim.hpp"
#include "service_cli.hpp"

#include <systemd/sd-daemon.h>

namespace gpilot {
namespace {

// The flight service: holds the latest inputs, ticks the bridge, drives the chosen backend.
class FlightService {
 public:
  FlightService(const Config& config, BusNode& node)
      : node_(node),
        fp_(config.section<FlightParams>("flight")),
        sim_params_(config.section<SimParams>("sim")),
        mav_params_(config.section<MavlinkParams>("mavlink")),
        bridge_(fp_) {
    // flight.backend, mavlink.autopilot and mavlink.endpoint were checked before the bus started (the sections'
    // check(), flight_params.hpp): only sim, mavlink and none reach here, with a known autopilot and an endpoint
    // that parses.
    if (fp_.backend == "sim") {
      sim_.emplace(sim_params_);
    } else if (fp_.backend == "mavlink") {
      link_ = std::make_unique<mavlink::UdpLink>(mavlink::parse_endpoint(mav_params_.endpoint));
      session_.emplace(mav_params_);
      if (!mav_params_.signing_key.empty()) {
        try {
          session_->enable_signing(load_bus_key(mav_params_.signing_key).bytes,
                                   static_cast<uint8_t>(mav_params_.signing_link_id));
        } catch (const std::runtime_error& e) {
          throw ConfigError(std::string("mavlink.signing_key: ") + e.what());
        }
      }
      gate_.emplace(mavlink::offboard_loss_param(mav_params_.autopilot), fp_.max_autopilot_loss_s,
                    mav_params_.param_timeout_s);
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
      node_.every(1.0 / mav_params_.heartbeat_hz, [this] {
        session_->set_time(node_.now());
        link_->send(session_->heartbeat());
      });
      node_.every(0.002, [this] { poll_mavlink(); });
      node_.every(1.0, [this] { report_link(); });
      link_->send(session_->heartbeat());
    }
    node_.set_state(health_t::STATE_OK, "backend " + fp_.backend + ", not engaged");
    // The watchdog: its period comes from the supervisor (WATCHDOG_USEC); pinged at a quarter of it by a timer of
    // this loop (not a thread of its own, and not tied to setpoint_rate_hz, which may be slower than the deadline):
    // a loop that stops, stops the pings.
    uint64_t watchdog_usec = 0;
    if (sd_watchdog_enabled(0, &watchdog_usec) > 0)
      node_.every(static_cast<double>(watchdog_usec) * 1e-6 / 4, [] { sd_notify(0, "WATCHDOG=1"); });
    sd_notify(0, "READY=1");
  }

  // Tells the supervisor (systemd, gpilot-launch) that the process is on its way out: not frozen.
  static void stopping() { sd_notify(0, "STOPPING=1"); }

 private:
  void control(const flight_control_t& m) {
    const OperatorRequest r = to_core(m);
    if (operator_.repeat(r)) return;
    if (gate_ && !gate_check(m, r)) return;
    apply_control(m, r);
  }

  // With MAVLink, an ENGAGE waits for the autopilot's offboard-loss parameter (EngageGate): false while it does
  // (or when it was refused); any other request cancels a pending ENGAGE and goes on.
  bool gate_check(const flight_control_t& m, const OperatorRequest& r) {
    if (m.command != flight_control_t::COMMAND_ENGAGE) {
      gate_->cancel();
      return true;
    }
    if (refused_ && refused_->utime == r.utime && refused_->seq == r.seq && refused_->source == r.source) return false;
    if (gate_->engage_requested(monotonic_utime()) == mavlink::EngageGate::Action::Request) {
      pending_engage_ = m;
      link_->send(session_->param_request_read(gate_->param()));
    }
    return false;
  }

  // What the gate says, from poll_mavlink (an answer) and tick (time).
  void gate_act(mavlink::EngageGate::Action a) {
    using A = mavlink::EngageGate::Action;
    if (a == A::Request) link_->send(session_->param_request_read(gate_->param()));
    if (a == A::Engage) {
      log_info("the autopilot's %s is %.2f s (<= %.2f): engaging", gate_->param().c_str(), gate_->last_value(),
               fp_.max_autopilot_loss_s);
      refused_.reset();
      apply_control(pending_engage_, to_core(pending_engage_));
    }
    if (a == A::Refuse) {
      const std::string why = "refusing to engage: " + gate_->why();
      log_warn("%s", why.c_str());
      refused_ = to_core(pending_engage_);
      // An ENGAGE while engaged re-reads the parameter too: changed on the autopilot since, the answer now
      // stands, and the vehicle hovers (as a DISENGAGE would leave it).
      in_.engaged = false;
      node_.reject(why);
      node_.set_state(health_t::STATE_DEGRADED, why);
    }
  }

  void apply_control(const flight_control_t& m, const OperatorRequest& r) {
    std::string why;
    const VehicleAction action = operator_.apply(r, in_, &why);
    if (!why.empty()) {
      node_.reject(why);
      return;
    }
    if (m.command == flight_control_t::COMMAND_ENGAGE) setpoints_since_engage_ = 0;
    switch (action) {
      case VehicleAction::Land:
        if (sim_) sim_->land();
        if (session_) link_->send(session_->land());
        break;
      case VehicleAction::Arm:
        if (sim_) sim_->arm();
        if (session_) link_->send(session_->arm(true));
        break;
      case VehicleAction::Disarm:
        if (sim_) sim_->disarm();
        if (session_) link_->send(session_->arm(false));
        break;
      case VehicleAction::Takeoff:
        if (sim_) sim_->takeoff(m.takeoff_altitude);
        if (session_) link_->send(session_->takeoff(m.takeoff_altitude));
        break;
      case VehicleAction::None: break;
    }
    node_.set_state(health_t::STATE_OK, "backend " + fp_.backend + (in_.engaged ? ", ENGAGED" : ", not engaged") +
                                            (in_.landing ? ", landing" : "") + " (last request from " + m.source + ")");
  }

  void tick() {
    if (gate_) gate_act(gate_->on_time(monotonic_utime()));
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
      for (; foreign_seen_ < link_->foreign(); ++foreign_seen_)
        node_.reject("MAVLink: a datagram from " + link_->last_foreign() + ", not the autopilot at " + mav_params_.endpoint);
      for (int64_t i = rejected_before; i < session_->parser().rejected(); ++i)
        node_.reject(std::string("MAVLink: ") + session_->parser().last_reject());
      for (const auto& v : session_->take_param_values()) gate_act(gate_->on_param_value(v));
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
      node_.set_state(health_t::STATE_OK, "autopilot at " + mav_params_.endpoint +
                                              (session_->signing() ? " (signed)" : " (unsigned)") +
                                              (in_.engaged ? ", ENGAGED" : ""));
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
  int64_t foreign_seen_ = 0;
  std::optional<mavlink::MavlinkSession> session_;
  OperatorState operator_;
  int setpoints_since_engage_ = 0;
  std::optional<mavlink::EngageGate> gate_;   // MAVLink only
  flight_control_t pending_engage_{};         // the ENGAGE waiting for the gate
  std::optional<OperatorRequest> refused_;    // the last ENGAGE refused (its repeats are not asked again)
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
    FlightService::stopping();
    return 0;
  });
}
