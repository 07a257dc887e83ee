#pragma once
// Test support of hapticctrl-mujoco's process tests: a shipped scene run through the real core,
// UDP bridge and program with a scripted operator (hapticctrl-hmi play --hand), and whether the
// engine kept real time.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "support/controller_stack.hpp"
#include "support/json_fields.hpp"
#include "support/network_scenario.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {

using namespace std::chrono_literals;

inline const std::string kScenes = HAPTICCTRL_MUJOCO_SCENES;

/// What a scene's run does: the scripted operator's push (N, base frame; a spring-damper hand,
/// 100 N/m and 5 N.s/m, holding the handle: hapticctrl-hmi play --hand) ramped in over 0.5 s from
/// `push_at` s on and held past the run's end, and the run's length.
struct SceneCase {
  const char* scene;
  std::vector<std::string> push;  // fx fy fz tx ty tz; empty: no push
  double push_at = 1.5;
  double duration = 4.0;
  int delay_ms = 0;  // one way, through hapticctrl-netem
  [[nodiscard]] std::string name() const {
    return std::string(scene) + (delay_ms > 0 ? "_" + std::to_string(delay_ms) + "ms" : "");
  }
};

// NOLINTNEXTLINE(readability-identifier-naming): GoogleTest's name
inline void PrintTo(const SceneCase& c, std::ostream* os) {
  *os << c.name();
}

inline int run_hmi(const ControllerStack& stack, std::vector<std::string> args) {
  args.insert(args.begin(), {"--instance", stack.instance()});
  SpawnedProcess hmi(HAPTICCTRL_HMI_BINARY, args);
  return hmi.wait(20s);
}

/// The scene run to its end with the case's push; its JSON summary ("" if it failed).
inline std::string run_scene(const ControllerStack& stack, const SceneCase& c) {
  std::optional<Relay> relay;
  if (c.delay_ms > 0) {
    relay.emplace(stack.port(), std::vector<std::string>{"--delay-ms", std::to_string(c.delay_ms)});
  }
  const std::uint16_t port = relay ? relay->port() : stack.port();
  SpawnedProcess mujoco(
      HAPTICCTRL_MUJOCO_BINARY,
      {"--model", kScenes + "/" + c.scene + ".xml", "--server", "127.0.0.1:" + std::to_string(port),
       "--headless", "--json", "--duration", std::to_string(c.duration)});
  if (!c.push.empty()) {
    std::this_thread::sleep_for(std::chrono::duration<double>(c.push_at));
    const std::string sequence = "/tmp/hapticctrl-scene-" + std::to_string(getpid()) + ".seq";
    std::string wrench;
    for (const std::string& v : c.push) {
      wrench += " " + v;
    }
    std::ofstream(sequence) << "0 0 0 0 0 0 0\n0.5" << wrench << "\n"
                            << c.duration - c.push_at + 0.5 << wrench << "\n";
    const std::string log = "/tmp/hapticctrl-scene-" + std::to_string(getpid()) + ".csv";
    EXPECT_EQ(run_hmi(stack, {"play", sequence, "--hand", "100,5", "--log", log}), 0);
    std::remove(sequence.c_str());
    std::remove(log.c_str());
  }
  const int status = mujoco.wait(std::chrono::seconds(static_cast<int>(c.duration) + 20));
  EXPECT_EQ(status, 0) << mujoco.err();
  std::printf("%s: %s", c.name().c_str(), mujoco.out().c_str());
  return status == 0 ? mujoco.out() : std::string{};
}

/// Whether the engine kept real time in a run (its summary): below 95 % of the model's steps per
/// second with steps dropped after a stall, the machine took the engine's time, and the physics
/// judged over wall-clock windows is not the scene's (BlockPush beside the whole suite: 28 mm in
/// place of 81, still moving at 36 mm/s when judged, 2026-12-06).
inline bool engine_kept_real_time(const std::string& name, const std::string& summary) {
  const double rate = json_number(summary, "steps_per_second");
  const double model = json_number(summary, "model_steps_per_second");
  if (rate < 0.95 * model && json_number(summary, "steps_dropped") > 0) {
    std::printf("%s: %.0f of %.0f steps/s with steps dropped after a stall: tried again\n",
                name.c_str(), rate, model);
    return false;
  }
  return true;
}

}  // namespace hapticctrl::test
