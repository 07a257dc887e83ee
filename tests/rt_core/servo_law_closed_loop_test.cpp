// Closed-loop scenarios of the control law on the simulated arm (label sim): gravity
// compensation, brakes, coupling equilibrium, passivity under delay and loss.
#include <gtest/gtest.h>

#include <cstdio>
#include <deque>
#include <memory>
#include <random>

#include "hapticctrl/rt_core/arm_simulator.hpp"
#include "hapticctrl/rt_core/servo_law.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "support/default_dynamics.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

using test::default_dynamics;

constexpr Duration kDt = 1ms;
const Vector6d kReady = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();

/// The simulated arm driven by the law at 1 kHz, as the servo does.
struct Loop {
  explicit Loop(const Vector6d& start, const LawConfig& config = {})
      : arm(default_dynamics(), SimulatorOptions{}, start, force.get()),
        law(default_dynamics(), config) {
    arm.set_supply(true);
    in.dt = kDt;
    in.logical.powered = true;
  }
  void push(const Vector6d& wrench) {
    shm::ForcePayload p;
    for (int i = 0; i < 6; ++i) {
      p.wrench[static_cast<std::size_t>(i)] = wrench(i);
    }
    force->publish(p, 0);
  }
  void cycle() {
    arm.get_measures(in.measures);
    law.compute(in, false, out);
    arm.send_commands(out.commands, in.now, kDt);
    in.now += kDt;
    ++in.cycle;
  }
  Vector3d handle() const { return arm.simulator().chain().handle_position; }

  std::unique_ptr<shm::SeqlockCell<shm::ForcePayload>> force =
      std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  SimulatedArm arm;
  ServoLaw law;
  ServoInputs in;
  ServoOutputs out;
};

TEST(ClosedLoop, GravityCompensationHoldsTheHandleFromSeveralPoses) {
  // Poses spread over the workspace box (handle at (0.63, 0, 0.23), (0.52, 0.18, 0.14),
  // (0.63, -0.17, 0.16), (0.40, 0.11, 0.14) m), wrist joints far from zero.
  const std::array<Vector6d, 4> poses{kReady,
                                      (Vector6d() << 0.3, -0.7, 1.4, 0.5, 0.3, -0.4).finished(),
                                      (Vector6d() << -0.3, -0.4, 1.0, -0.6, -0.5, 0.8).finished(),
                                      (Vector6d() << 0.1, -0.9, 1.8, 1.0, 0.9, 0.3).finished()};
  for (const Vector6d& pose : poses) {
    Loop loop(pose);
    const Vector3d start = loop.handle();
    for (int k = 0; k < 10'000; ++k) {
      loop.cycle();
    }
    EXPECT_LT((loop.handle() - start).norm(), 1e-3) << "pose " << pose.transpose();
  }
}

TEST(ClosedLoop, WithoutGravityCompensationTheArmWouldFall) {
  // The same loop with the supply on but the law unpowered: brakes hold; released brakes with
  // zero torque fall. Guards the test above against a simulator that cannot move.
  ArmSimulator sim(default_dynamics(), SimulatorOptions{}, kReady);
  for (int k = 0; k < 1000; ++k) {
    sim.step(Vector6d::Zero(), Vector6d::Zero(), 1e-3, false);
  }
  ChainState start;
  default_dynamics().forward_kinematics(kReady, start);
  EXPECT_GT((sim.chain().handle_position - start.handle_position).norm(), 0.05);
}

TEST(ClosedLoop, UnpoweredBrakesHoldUnderOperatorForce) {
  Loop loop(kReady);
  loop.in.logical.powered = false;
  loop.push((Vector6d() << 20, -10, -20, 0, 0, 0).finished());
  const Vector3d start = loop.handle();
  for (int k = 0; k < 3000; ++k) {
    loop.cycle();
  }
  EXPECT_LT((loop.handle() - start).norm(), 1e-9);
}

TEST(ClosedLoop, CouplingBalancesTheOperatorForceAgainstAFixedObject) {
  Loop loop(kReady);
  ClientSample& client = loop.in.client;
  const Vector3d p = loop.handle();
  client.session_id = 1;
  client.command = ClientCommand::kVirtmech;
  client.object_attached = true;
  client.object_pose = {p.x(), p.y(), p.z(), 0, 0, 0, 1};
  client.object_mass = 0.5;
  client.time_step = 1e-3;
  loop.in.client_valid = true;  // the client keeps sending the same pose: age stays 0
  const Vector6d push = (Vector6d() << 8, -3, 4, 0, 0, 0).finished();
  loop.push(push);
  // Steady state, averaged over the last second: encoder quantisation and the velocity filter
  // leave a small jitter (about 0.1 N) around the equilibrium.
  Vector3d on_handle = Vector3d::Zero();
  Vector3d on_object = Vector3d::Zero();
  for (int k = 0; k < 6000; ++k) {
    loop.cycle();
    if (k >= 5000) {
      on_handle += loop.out.rendered_wrench.head<3>() / 1000.0;
      on_object += loop.out.object_wrench.head<3>() / 1000.0;
    }
  }
  const Vector3d operator_force = push.head<3>();
  EXPECT_LT((on_handle + operator_force).norm(), 0.01 * operator_force.norm())
      << "coupling on the handle: " << on_handle.transpose();
  EXPECT_LT((on_object - operator_force).norm(), 0.01 * operator_force.norm());
  EXPECT_NEAR((loop.handle() - p).norm(), operator_force.norm() / 2000.0, 2e-4)
      << "deflection = F / k";
}

/// Bilateral coupling through a delayed, lossy link: the client's object (0.2 kg, integrated at
/// 1 ms like a physics engine) is pushed by random smooth forces and by the coupling wrench that
/// reaches it; the controller sees the object's pose and twist `delay_ms` late, loses `loss` of
/// the samples both ways, and extrapolates.
struct PassivityRun {
  double lowest_energy = 0.0;  ///< lowest energy the passivity observer saw in the port
  double max_object_speed = 0.0;
  double max_handle_speed = 0.0;
  double channel_out = 0.0;     ///< the core's end of the channel, after its PC
  double client_in = 0.0;       ///< what the client put in
  std::uint64_t pc_active = 0;  ///< cycles the core's channel PC acted
};

PassivityRun run_delayed_coupling(bool guard, int delay_ms, double loss, unsigned seed,
                                  bool two_port = false, double gravity = 0.0) {
  LawConfig config;
  config.passivity_guard = guard;
  Loop loop(kReady, config);
  std::mt19937 rng(seed);
  std::bernoulli_distribution lost(loss);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double mass = 0.2;
  Vector3d x = loop.handle();
  Vector3d v = Vector3d::Zero();
  Vector3d push = Vector3d::Zero();
  Vector3d coupling = Vector3d::Zero();
  std::deque<std::array<double, 7>> to_controller;  // state and the client's channel energy
  double client_in = 0.0;  // what a 1.1 client library reports (ChannelPassivity)
  std::deque<Vector3d> to_client;
  loop.in.client.session_id = 1;
  loop.in.client.command = ClientCommand::kVirtmech;
  loop.in.client.object_attached = true;
  loop.in.client.object_mass = mass;
  loop.in.client.time_step = 1e-3;
  loop.in.client.object_pose = {x.x(), x.y(), x.z(), 0, 0, 0, 1};
  loop.in.client_valid = true;
  PassivityRun result;
  for (int k = 0; k < 10'000; ++k) {
    to_controller.push_back({x.x(), x.y(), x.z(), v.x(), v.y(), v.z(), client_in});
    loop.in.client_age += 1ms;
    loop.in.client_silence += 1ms;
    loop.in.new_sample = false;
    if (static_cast<int>(to_controller.size()) > delay_ms) {
      const auto state = to_controller.front();
      to_controller.pop_front();
      if (!lost(rng)) {
        // What the protocol's timing echo tells the core (docs/control.md): the sample's age is
        // the way in; the loop is the answer's way out, the client's step and the way back.
        loop.in.client.object_pose = {state[0], state[1], state[2], 0, 0, 0, 1};
        loop.in.client.object_twist = {state[3], state[4], state[5], 0, 0, 0};
        loop.in.client.energy_in = two_port ? state[6] : -1.0;
        loop.in.client_age = delay_ms * 1ms;
        loop.in.client_silence = 0ns;
        loop.in.new_sample = true;
        loop.in.loop_delay = (2 * delay_ms + 1) * 1ms;
      }
    }
    loop.cycle();
    to_client.push_back(loop.out.object_wrench.head<3>());
    if (static_cast<int>(to_client.size()) > delay_ms) {
      const Vector3d f = to_client.front();
      to_client.pop_front();
      if (!lost(rng)) {
        coupling = f;
      }
    }
    // Drawn one by one: the order in which a call's arguments are evaluated is the compiler's
    // (GCC right to left, clang left to right), and each order is another scenario. This is
    // GCC's, in which the figures below were measured. (In clang's, 2026-12-07, the two-port
    // case at 2 ms dipped to -14.5 mJ: docs/control.md, Not yet.)
    const double push_z = noise(rng);
    const double push_y = noise(rng);
    const double push_x = noise(rng);
    push = 0.99 * push + 0.1 * Vector3d(push_x, push_y, push_z);  // ~1 N, smooth
    v += (coupling + push + Vector3d(0, 0, -gravity * mass)) / mass * 1e-3;
    x += v * 1e-3;
    client_in += std::max(0.0, -coupling.dot(v)) * 1e-3;
    const double e = loop.law.observed_energy();
    result.lowest_energy = std::isfinite(e) ? std::min(result.lowest_energy, e) : -1e9;
    result.max_object_speed =
        std::isfinite(v.norm()) ? std::max(result.max_object_speed, v.norm()) : 1e9;
    result.max_handle_speed =
        std::max(result.max_handle_speed, loop.out.handle_twist.head<3>().norm());
  }
  result.channel_out = loop.out.channel_energy_out;
  result.client_in = client_in;
  result.pc_active = loop.law.counters().channel_pc_active;
  return result;
}

TEST(ClosedLoop, PassivityGuardKeepsTheCouplingPortPassiveUnderDelayAndLoss) {
  for (const int delay : {0, 2, 5, 10}) {
    const PassivityRun run =
        run_delayed_coupling(true, delay, 0.10, 42U + static_cast<unsigned>(delay));
    // The guard's damping is bounded by what the device renders stably (20 N·s/m), so a deficit
    // can outlast one period. Measured worst: 0.086 J with gains blind to the delay
    // (2026-11-22); 0.0039 J with gains derived from the measured loop (2026-12-02). Stated
    // tolerance 0.01 J.
    EXPECT_GT(run.lowest_energy, -0.01) << "delay " << delay << " ms";
    std::printf("guard on, delay %d ms: lowest %.4f J, object %.2f m/s, handle %.2f m/s\n", delay,
                run.lowest_energy, run.max_object_speed, run.max_handle_speed);
    RecordProperty("lowest_energy_mJ_delay_" + std::to_string(delay),
                   static_cast<int>(run.lowest_energy * 1000));
  }
}

TEST(ClosedLoop, TwoPortPassivityKeepsTheChannelWithinWhatTheClientPutIn) {
  for (const int delay : {2, 10, 20}) {
    PassivityRun run =
        run_delayed_coupling(true, delay, 0.10, 7U + static_cast<unsigned>(delay), true, 9.81);
    std::printf(
        "two-port, delay %d ms, weighted: lowest %.4f J, object %.2f m/s, handle %.2f m/s,"
        " channel out %.4f J of %.4f J put in, PC active %llu cycles\n",
        delay, run.lowest_energy, run.max_object_speed, run.max_handle_speed, run.channel_out,
        run.client_in, static_cast<unsigned long long>(run.pc_active));
    // The core's PC gives way at 0.5 m/s and by 5 cm at most; beyond, it is saturated (20 ms:
    // 0.074 J over 10 s, 2026-12-02) and the one-port guard at the handle remains.
    EXPECT_LE(run.channel_out, run.client_in + 0.1) << "the core's end stays within the client's";
    EXPECT_GT(run.lowest_energy, -0.01) << "delay " << delay << " ms";
    EXPECT_LT(run.max_handle_speed, 1.0) << "delay " << delay << " ms";
  }
}

TEST(ClosedLoop, WithoutTheGuardDelayAndLossMakeTheUserPortActive) {
  const PassivityRun run = run_delayed_coupling(false, 10, 0.10, 52U);
  std::printf("guard off, delay 10 ms: lowest %.4f J, object %.2f m/s, handle %.2f m/s\n",
              run.lowest_energy, run.max_object_speed, run.max_handle_speed);
  EXPECT_LT(run.lowest_energy, -1.0) << "the unguarded port pumps energy into the hand";
}

/// A client in a joint-space mode, its command in force from the first cycle.
void joint_client(Loop& loop, ClientCommand command) {
  loop.in.client_valid = true;
  loop.in.client.session_id = 1;
  loop.in.client.command = command;
  loop.in.client.joint_command = true;
}

TEST(ClosedLoop, ArticularTakesEachJointToItsTargetAndHoldsItThere) {
  Loop loop(kReady);
  joint_client(loop, ClientCommand::kArticular);
  // A target whose handle stays inside the workspace box (its wall would hold the arm back).
  const std::array<double, 6> target{0.2, -0.5, 1.1, 0.5, -0.4, 0.6};
  loop.in.client.joint_target = target;
  // The speed as 100 ms of travel: the encoders' quantisation makes single-cycle speeds noisy.
  std::deque<Vector6d> path;
  double fastest = 0.0;
  Vector6d settled = Vector6d::Zero();
  for (int k = 0; k < 4000; ++k) {
    loop.cycle();
    path.push_back(loop.in.measures.position);
    if (path.size() > 100) {
      fastest = std::max(fastest, (path.back() - path.front()).cwiseAbs().maxCoeff() / 0.1);
      path.pop_front();
    }
    if (k == 3000) {
      settled = loop.in.measures.position;
    }
  }
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(loop.in.measures.position(i), target[static_cast<std::size_t>(i)], 0.01)
        << "joint " << i + 1;
  }
  EXPECT_EQ(loop.law.counters().workspace_walls, 0U);
  EXPECT_LT((loop.in.measures.position - settled).cwiseAbs().maxCoeff(), 1e-3) << "held";
  // The set points move at 1 rad/s; a joint that lags its set point catches up a little faster
  // (1.30 rad/s measured, 2026-12-06).
  EXPECT_LT(fastest, 1.5) << "the joints follow set points that move at 1 rad/s";
}

/// ARTICULAR_IMPEDANCE: a client that drives joint 1 with 1 N.m into a stiff, damped joint wall at
/// 0.2 rad (200 N.m/rad, 2 N.m.s/rad, as ViSP's joint-limit test renders its limits) that it
/// computes from the joint's position and speed `delay_ms` old (its link). Returns joint 1's
/// largest speed over the last second, as 20 ms of travel (the encoders quantise single cycles).
double delayed_joint_wall(bool guard, int delay_ms) {
  LawConfig config;
  config.passivity_guard = guard;
  Loop loop(kReady, config);
  joint_client(loop, ClientCommand::kArticularImpedance);
  std::deque<std::pair<double, double>> seen;  // position, speed
  std::deque<double> path;
  double fastest_late = 0.0;
  for (int k = 0; k < 5000; ++k) {
    seen.emplace_back(loop.in.measures.position(0), loop.in.measures.velocity(0));
    if (static_cast<int>(seen.size()) > delay_ms + 1) {
      seen.pop_front();  // the front is delay_ms cycles old
    }
    const auto [q, qd] = seen.front();
    const double wall = q > 0.2 ? std::max(0.0, 200.0 * (q - 0.2) + 2.0 * qd) : 0.0;
    loop.in.client.joint_torque[0] = 1.0 - wall;
    loop.cycle();
    path.push_back(loop.in.measures.position(0));
    if (path.size() > 20) {
      path.pop_front();
    }
    if (k >= 4000) {
      fastest_late = std::max(fastest_late, std::abs(path.back() - path.front()) / 0.02);
    }
  }
  return fastest_late;
}

TEST(ClosedLoop, TheJointGuardStillsAJointWallTheClientRendersLate) {
  EXPECT_LT(delayed_joint_wall(false, 0), 0.01) << "on time, the damped wall holds the joint";
  EXPECT_GT(delayed_joint_wall(false, 20), 0.1) << "20 ms late and unguarded, it chatters";
  EXPECT_LT(delayed_joint_wall(true, 20), 0.01) << "guarded, the joint rests on it";
}

TEST(ClosedLoop, ATorqueDrivesEachJointIntoItsWallAndTheBoundBitsSayIt) {
  // Each joint in turn, toward each limit, with 0.8 of its continuous torque (the others held
  // where they are by nothing but gravity compensation): the guard lets the free joint go (at
  // most its continuous torque per 1 rad/s of damping) and the soft wall stops it.
  for (int joint = 0; joint < 6; ++joint) {
    for (const double sign : {1.0, -1.0}) {
      Loop loop(kReady);
      joint_client(loop, ClientCommand::kArticularImpedance);
      const auto j = static_cast<std::size_t>(joint);
      loop.in.client.joint_torque[j] =
          sign * 0.8 * default_dynamics().model().joints[j].torque_continuous;
      bool bound = false;
      for (int k = 0; k < 8000 && !bound; ++k) {
        loop.cycle();
        bound =
            (loop.out.joint_bounds &
             (shm::state_bits::joint_bound(static_cast<unsigned>(joint), sign > 0) |
              (joint == 1 || joint == 2 ? shm::state_bits::joint_bound(6, sign > 0) : 0U))) != 0;
      }
      EXPECT_TRUE(bound) << "joint " << joint + 1 << (sign > 0 ? " up" : " down") << " at "
                         << loop.in.measures.position(joint);
    }
  }
}

}  // namespace
}  // namespace hapticctrl::rt_core
