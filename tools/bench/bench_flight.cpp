// Benchmarks of the decide and flight cores (Google Benchmark): Alg. 3 per observation, one bridge tick, one
// simulator step, MAVLink setpoint encoding and state-datagram parsing. Inputs are built before timing.
#include <benchmark/benchmark.h>

#include <vector>

#include "decide/gesture_decider.hpp"
#include "flight/flight_bridge.hpp"
#include "flight/mavlink/session.hpp"
#include "flight/quadrotor_sim.hpp"

namespace gpilot {
namespace {

void BM_DecideUpdate(benchmark::State& state) {
  GestureDecider decider{DecideParams{}};
  HandObservation o;
  o.track_id = 1;
  o.kind = HandObservation::Kind::Out;
  o.vector = {-60, 10};
  o.user_box_width = 120;
  int64_t i = 0;
  for (auto _ : state) {
    o.utime = 40000 * i;
    o.seq = i++;
    benchmark::DoNotOptimize(decider.update(o));
  }
}
BENCHMARK(BM_DecideUpdate);

void BM_BridgeUpdate(benchmark::State& state) {
  FlightBridge bridge{FlightParams{}};
  BridgeInputs in;
  GestureCommand c;
  c.track_id = 1;
  c.mode = GestureMode::Fine;
  c.direction[0] = -0.5;
  c.user_box_width = 120;
  in.command = c;
  UserTrack t;
  t.tracking = true;
  t.track_id = 1;
  t.image_width = 640;
  t.box[0] = 300;
  t.box[2] = 120;
  t.box[3] = 360;
  in.track = t;
  in.vehicle = VehicleState{};
  in.engaged = true;
  int64_t now = 1700000000000000;
  for (auto _ : state) {
    in.now = in.command_received = in.track_received = in.vehicle_received = (now += 20000);
    benchmark::DoNotOptimize(bridge.update(in));
  }
}
BENCHMARK(BM_BridgeUpdate);

void BM_SimStep(benchmark::State& state) {
  QuadrotorSim sim{SimParams{}};
  Setpoint sp;
  sp.velocity[1] = -0.5;
  sp.yaw_rate = 0.1;
  for (auto _ : state) {
    sim.step(sp, 0.01);
    benchmark::DoNotOptimize(sim.state(0));
  }
}
BENCHMARK(BM_SimStep);

void BM_MavlinkEncodeSetpoint(benchmark::State& state) {
  mavlink::MavlinkSession session{MavlinkParams{}};
  Setpoint sp;
  sp.velocity[0] = 0.25;
  sp.velocity[1] = -0.5;
  sp.yaw_rate = 0.1;
  int64_t now = 0;
  for (auto _ : state) benchmark::DoNotOptimize(session.setpoint(sp, now += 20000));
}
BENCHMARK(BM_MavlinkEncodeSetpoint);

void BM_MavlinkParseStateDatagram(benchmark::State& state) {
  mavlink::LocalPositionNed pos;
  pos.x = 1.5f;
  pos.vx = 0.25f;
  mavlink::Attitude att;
  att.yaw = 0.5f;
  std::vector<uint8_t> datagram;
  for (const auto& f : {mavlink::encode_frame({0, 1, 1, mavlink::Attitude::kId, mavlink::pack(att)}),
                        mavlink::encode_frame({1, 1, 1, mavlink::LocalPositionNed::kId, mavlink::pack(pos)})})
    datagram.insert(datagram.end(), f.begin(), f.end());
  mavlink::MavlinkSession session{MavlinkParams{}};
  for (auto _ : state) benchmark::DoNotOptimize(session.on_datagram(datagram.data(), datagram.size(), 0));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(datagram.size()));
}
BENCHMARK(BM_MavlinkParseStateDatagram);

}  // namespace
}  // namespace gpilot
