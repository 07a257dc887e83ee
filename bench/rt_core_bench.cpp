// Cost of one servo cycle (simulator + kinematics + control law), and of its parts, with its
// share of a 1 ms and a 100 µs period.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>

#include "hapticctrl/rt_core/arm_simulator.hpp"
#include "hapticctrl/rt_core/servo_law.hpp"
#include "support/ratio_reporter.hpp"

namespace {

using namespace hapticctrl;
using namespace hapticctrl::rt_core;

/// The arm's ready pose (a function: a static Eigen vector's construction is not noexcept).
Vector6d ready() {
  return (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();
}

const ArmDynamics& dynamics() {
  static const ArmDynamics d(load_arm_model(default_arm_model_path()));
  return d;
}

ServoInputs coupled_inputs() {
  ServoInputs in;
  in.dt = std::chrono::milliseconds(1);
  in.logical.powered = true;
  in.client.session_id = 1;
  in.client.command = ClientCommand::kVirtmech;
  in.client.object_attached = true;
  in.client.object_pose = {0.63, 0.01, 0.23, 0, 0, 0, 1};
  in.client.object_twist = {0.02, 0, 0, 0, 0, 0.1};
  in.client.object_mass = 0.3;
  in.client.time_step = 1e-3;
  in.client_valid = true;
  return in;
}

void BM_ForwardKinematicsAndJacobian(benchmark::State& state) {
  ChainState chain;
  const Vector6d q = ready();
  for (auto _ : state) {
    dynamics().forward_kinematics(q, chain);
    benchmark::DoNotOptimize(dynamics().jacobian(chain));
  }
}
BENCHMARK(BM_ForwardKinematicsAndJacobian);

void BM_MassMatrix(benchmark::State& state) {
  ChainState chain;
  dynamics().forward_kinematics(ready(), chain);
  for (auto _ : state) {
    benchmark::DoNotOptimize(dynamics().mass_matrix(chain));
  }
}
BENCHMARK(BM_MassMatrix);

void BM_ControlLaw(benchmark::State& state) {
  ServoLaw law(dynamics());
  ServoInputs in = coupled_inputs();
  in.measures.position = ready();
  in.measures.supply_on = true;
  ServoOutputs out;
  for (auto _ : state) {
    law.compute(in, false, out);
    benchmark::DoNotOptimize(out.commands.torque.data());
  }
}
BENCHMARK(BM_ControlLaw);

void BM_SimulatorStep1ms(benchmark::State& state) {
  ArmSimulator sim(dynamics(), SimulatorOptions{}, ready());
  const Vector6d torque = dynamics().gravity_torque(sim.chain());
  for (auto _ : state) {
    sim.step(torque, Vector6d::Zero(), 1e-3, false);
  }
}
BENCHMARK(BM_SimulatorStep1ms);

/// One full cycle as the SERVO runs it: measures, law, commands (simulator integration).
void run_full_cycle(benchmark::State& state, Duration period) {
  auto force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  SimulatedArm arm(dynamics(), SimulatorOptions{}, ready(), force.get());
  arm.set_supply(true);
  ServoLaw law(dynamics());
  ServoInputs in = coupled_inputs();
  in.dt = period;
  ServoOutputs out;
  for (auto _ : state) {
    arm.get_measures(in.measures);
    law.compute(in, false, out);
    arm.send_commands(out.commands, TimePoint{}, period);
  }
}

void BM_FullCycle1ms(benchmark::State& state) {
  run_full_cycle(state, std::chrono::milliseconds(1));
}
BENCHMARK(BM_FullCycle1ms);

/// At 100 µs the simulator runs a single sub-step.
void BM_FullCycle100us(benchmark::State& state) {
  run_full_cycle(state, std::chrono::microseconds(100));
}
BENCHMARK(BM_FullCycle100us);

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::bench::run_with_ratios(
      argc, argv,
      {{"BM_ControlLaw", "BM_ForwardKinematicsAndJacobian"},
       {"BM_FullCycle1ms", "BM_SimulatorStep1ms"}},
      [](const hapticctrl::bench::RatioReporter& reporter) {
        const double cycle_1ms = reporter.ns("BM_FullCycle1ms");
        const double cycle_100us = reporter.ns("BM_FullCycle100us");
        if (cycle_1ms > 0 && cycle_100us > 0) {
          std::printf(
              "\nshare of the period: 1 ms cycle %.0f ns = %.2f %% of 1 ms; "
              "100 us cycle %.0f ns = %.2f %% of 100 us\n",
              cycle_1ms, cycle_1ms / 1e4, cycle_100us, cycle_100us / 1e3);
        }
      });
}
