// The flight stage on a bus: the latest GESTURE_CMD, USER_TRACK, FLIGHT_CONTROL (and VEHICLE_STATE with backend
// none) in; FLIGHT_SETPOINT at flight.setpoint_rate_hz always (zero with reasons when unsafe), VEHICLE_STATE from
// the built-in simulator (backend sim) or the autopilot (backend mavlink, MAVLink v2 over UDP: the socket is
// the adapter's, mavlink/udp_link, not the core's). With MAVLink, what the autopilot says that the stage acts on
// (HEARTBEAT, PARAM_VALUE) is published on AUTOPILOT as it arrives and taken from that message, and ENGAGE first
// reads the autopilot's offboard-loss failsafe time (autopilot_watch.hpp): a replay reads the same messages
// from the log and decides the same. Used by gpilot-flight and gpilot-replay.
#include "flight_service.hpp"

#include <cmath>
#include <memory>
#include <optional>

#include "autopilot_watch.hpp"
#include "bus_key.hpp"
#include "flight_bridge.hpp"
#include "flight_channels.hpp"
#include "flight_messages.hpp"
#include "log.hpp"
#include "mavlink/offboard_loss.hpp"
#include "mavlink/session.hpp"
#include "mavlink/udp_link.hpp"
#include "quadrotor_sim.hpp"

namespace gpilot {
namespace {

// The flight service: holds the latest inputs, ticks the bridge, drives the chosen backend.
// The receipt time the bridge judges staleness by is the time of the first tick that had the input (not the
// datagram's arrival): the tick times and which inputs each tick had are in the log (FLIGHT_SETPOINT's utime,
// latest_command_seq, track_utime), so a replay decides exactly as the live run did, while another process's
// arrival time (the logger's) reads a millisecond apart and would decide differently at the stale edge. The
// age is at most one tick (1 / flight.setpoint_rate_hz) shorter than since arrival.
class FlightService {
 public:
  FlightService(const Config& config, BusNode& node, VehicleSource vehicle)
      : node_(node),
        vehicle_source_(vehicle),
        fp_(config.section<FlightParams>("flight")),
        sim_params_(config.section<SimParams>("sim")),
        mav_params_(config.section<MavlinkParams>("mavlink")),
        bridge_(fp_) {
    // flight.backend, mavlink.autopilot and mavlink.endpoint were checked before the bus started (the sections'
    // check(), flight_params.hpp): only sim, mavlink and none reach here, with a known autopilot and an endpoint
    // that parses.
    if (fp_.backend == "mavlink")
      watch_.emplace(mavlink::offboard_loss_param(mav_params_.autopilot), fp_.max_autopilot_loss_s,
                     mav_params_.param_timeout_s, mav_params_.link_timeout_s);
    if (vehicle_source_ == VehicleSource::FromBus) return;  // the log's vehicle and autopilot: nothing to open
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
    }
  }

  void start() {
    subscribe(node_, flight_channels::kGestureCmd, [this](const gesture_cmd_t& m, int64_t) {
      in_.command = to_core(m);
      new_command_ = true;
    });
    subscribe(node_, flight_channels::kUserTrack, [this](const user_track_t& m, int64_t) {
      in_.track = to_core(m);
      new_track_ = true;
    });
    subscribe(node_, flight_channels::kFlightControl, [this](const flight_control_t& m, int64_t) {
      control_utime_ = m.utime;
      control(m);
    });
    if (fp_.backend == "none" || vehicle_source_ == VehicleSource::FromBus) {
      subscribe(node_, flight_channels::kVehicleState, [this](const vehicle_state_t& m, int64_t) { vehicle(m); });
    }
    if (watch_ && vehicle_source_ == VehicleSource::FromBus) {
      subscribe(node_, flight_channels::kAutopilot, [this](const autopilot_t& m, int64_t) { watch_->heard(to_core(m)); });
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
  }

 private:
  void control(const flight_control_t& m) {
    const OperatorRequest r = to_core(m);
    if (operator_.repeat(r)) return;
    if (watch_ && !gate_check(m, r)) return;
    apply_control(m, r);
  }

  // With MAVLink, an ENGAGE waits for the autopilot's offboard-loss parameter (AutopilotWatch, from the next
  // tick): false while it does (or when it was refused); any other request cancels a pending ENGAGE and goes on.
  bool gate_check(const flight_control_t& m, const OperatorRequest& r) {
    if (m.command != flight_control_t::COMMAND_ENGAGE) {
      watch_->cancel();
      return true;
    }
    if (refused_ && refused_->utime == r.utime && refused_->seq == r.seq && refused_->source == r.source) return false;
    if (!watch_->pending()) pending_engage_ = m;
    watch_->engage_requested();
    return false;
  }

  // What the watch decided at this tick (on the tick's time, from the AUTOPILOT messages the tick had).
  void watch_act(const AutopilotWatch::Decision& d) {
    if (d.request_param && session_) link_->send(session_->param_request_read(watch_->param()));
    if (d.engage) {
      log_info("the autopilot's %s is %.2f s (<= %.2f): engaging", watch_->param().c_str(), watch_->last_value(),
               fp_.max_autopilot_loss_s);
      refused_.reset();
      not_engaged_why_.clear();
      apply_control(pending_engage_, to_core(pending_engage_));
    }
    if (!d.refuse.empty()) {
      refused_ = to_core(pending_engage_);
      // An ENGAGE while engaged re-reads the parameter too: changed on the autopilot since, the answer now
      // stands, and the vehicle hovers (as a DISENGAGE would leave it).
      disengage("refusing to engage: " + d.refuse);
    }
    if (!d.link_lost.empty() && in_.engaged) disengage("disengaged: " + d.link_lost);
    else if (!d.link_lost.empty()) node_.set_state(health_t::STATE_DEGRADED, d.link_lost);
    if (d.link_back) {
      log_info("the autopilot's link is back (ENGAGE again to fly)");
      node_.set_state(health_t::STATE_OK, "the autopilot's link is back, not engaged");
    }
  }

  // Hover from this tick on, and say why (stderr, HEALTH).
  void disengage(const std::string& why) {
    log_warn("%s", why.c_str());
    in_.engaged = false;
    not_engaged_why_ = why;
    node_.reject(why);
    node_.set_state(health_t::STATE_DEGRADED, why);
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

  // A vehicle state as the bridge takes it: through its message, as a replay reads it from the log (the same
  // float values decide the height limits), received at the next tick.
  void vehicle(const vehicle_state_t& m) {
    in_.vehicle = to_core(m);
    new_vehicle_ = true;
  }

  void tick() {
    in_.now = node_.now();
    if (watch_) watch_act(watch_->tick(in_.now));
    if (new_command_) in_.command_received = in_.now;
    if (new_track_) in_.track_received = in_.now;
    if (new_vehicle_) in_.vehicle_received = in_.now;
    new_command_ = new_track_ = new_vehicle_ = false;
    last_ = bridge_.update(in_);
    flight_setpoint_t sp = to_message(last_);
    sp.control_utime = control_utime_;  // the operator's request it had (a replay applies it before this tick)
    publish(node_, flight_channels::kFlightSetpoint, sp);
    if (session_ && in_.engaged) {
      link_->send(session_->setpoint(last_, in_.now));
      // PX4 accepts OFFBOARD only once setpoints are streaming: ask after a short run of them.
      if (++setpoints_since_engage_ == 10 && mav_params_.set_mode_on_engage) link_->send(session_->engage_mode());
    }
  }

  void step_sim() {
    sim_->step(last_, 1.0 / sim_params_.rate_hz);
    const vehicle_state_t m = to_message(sim_->state(node_.now()), vehicle_state_t::SOURCE_SIMULATOR);
    publish(node_, flight_channels::kVehicleState, m);
    vehicle(m);
  }

  void poll_mavlink() {
    std::vector<uint8_t> buf;
    while (link_->receive(buf)) {
      const int64_t now = node_.now();
      const int64_t rejected_before = session_->parser().rejected();
      const auto state = session_->on_datagram(buf.data(), buf.size(), now);
      for (; foreign_seen_ < link_->foreign(); ++foreign_seen_)
        node_.reject("MAVLink: a datagram from " + link_->last_foreign() + ", not the autopilot at " + mav_params_.endpoint);
      for (int64_t i = rejected_before; i < session_->parser().rejected(); ++i)
        node_.reject(std::string("MAVLink: ") + session_->parser().last_reject());
      // What the autopilot said, on the bus as it arrived and taken from there (as a replay takes it).
      for (const auto& h : session_->take_heartbeats()) autopilot(to_message(h, now));
      for (const auto& v : session_->take_param_values()) autopilot(to_message(v, now));
      if (state) {
        const vehicle_state_t m = to_message(*state, vehicle_state_t::SOURCE_MAVLINK);
        publish(node_, flight_channels::kVehicleState, m);
        vehicle(m);
      }
    }
  }

  void autopilot(autopilot_t m) {
    m.seq = ++autopilot_seq_;
    publish(node_, flight_channels::kAutopilot, m);
    watch_->heard(to_core(m));
  }

  void report_link() {
    const int64_t now = node_.now();
    if (!in_.engaged && !not_engaged_why_.empty())
      node_.set_state(health_t::STATE_DEGRADED, not_engaged_why_);  // the last refusal or loss stands until an engage
    else if (!watch_->link_up() && watch_->ever_heard())
      node_.set_state(health_t::STATE_DEGRADED, "the autopilot's link is lost (" + mav_params_.endpoint + ")");
    else if (!session_->heard_autopilot())
      node_.set_state(health_t::STATE_DEGRADED, "no autopilot HEARTBEAT from " + mav_params_.endpoint);
    else if (!in_.vehicle || now - in_.vehicle_received > kMicrosPerSecond)
      node_.set_state(health_t::STATE_DEGRADED, "no LOCAL_POSITION_NED from " + mav_params_.endpoint + " for 1 s");
    else
      node_.set_state(health_t::STATE_OK, "autopilot at " + mav_params_.endpoint +
                                              (session_->signing() ? " (signed)" : " (unsigned)") +
                                              (in_.engaged ? ", ENGAGED" : ""));
  }

  BusNode& node_;
  VehicleSource vehicle_source_;
  FlightParams fp_;
  SimParams sim_params_;
  MavlinkParams mav_params_;
  FlightBridge bridge_;
  BridgeInputs in_;
  bool new_command_ = false, new_track_ = false, new_vehicle_ = false;  // arrived since the last tick
  int64_t control_utime_ = 0;                                           // the newest FLIGHT_CONTROL's utime
  Setpoint last_;
  std::optional<QuadrotorSim> sim_;
  std::unique_ptr<mavlink::UdpLink> link_;
  int64_t foreign_seen_ = 0;
  std::optional<mavlink::MavlinkSession> session_;
  OperatorState operator_;
  int setpoints_since_engage_ = 0;
  std::optional<AutopilotWatch> watch_;       // MAVLink only (live or replayed)
  int64_t autopilot_seq_ = 0;                 // AUTOPILOT messages published
  std::string not_engaged_why_;               // the last refusal or link loss, until an ENGAGE goes through
  flight_control_t pending_engage_{};         // the ENGAGE waiting for the gate
  std::optional<OperatorRequest> refused_;    // the last ENGAGE refused (its repeats are not asked again)
};

}  // namespace

std::shared_ptr<void> start_flight_service(const Config& config, BusNode& node, VehicleSource vehicle) {
  auto service = std::make_shared<FlightService>(config, node, vehicle);
  service->start();
  return service;
}

}  // namespace gpilot
