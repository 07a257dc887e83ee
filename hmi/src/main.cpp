// hapticctrl-hmi: the operator panel of a running hapticctrl-core (maps its shared memory).
// Without a command: the full-screen panel. With one: do it, wait for its effect, report.
// Exit: 0 done, 1 error or no effect within the timeout, 64 usage.
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/hmi/hmi_options.hpp"
#include "hapticctrl/hmi/operator.hpp"
#include "hapticctrl/hmi/panel.hpp"
#include "hapticctrl/hmi/sequence_player.hpp"
#include "hapticctrl/hmi/status.hpp"
#include "hapticctrl/hmi/wrench_sequence.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/shm/names.hpp"

namespace {

namespace hmi = hapticctrl::hmi;
namespace shm = hapticctrl::shm;
using hmi::ControllerStatus;
using hmi::HmiCommand;

bool needs_force(HmiCommand c) {
  return c == HmiCommand::kPanel || c == HmiCommand::kForce || c == HmiCommand::kZeroForce ||
         c == HmiCommand::kPlay;
}

void print_status(const ControllerStatus& s, bool json) {
  if (json) {
    std::printf("%s\n", hmi::status_json(s).c_str());
    return;
  }
  const auto& p = s.position.handle_pose;
  std::printf("instance '%s': %s, %s%s%s, cycle %llu, handle at (%.4f, %.4f, %.4f) m, client %s\n",
              s.instance.c_str(), shm::core_state_name(s.vp.core_state),
              s.powered() ? "powered" : "unpowered", s.emergency_stop() ? ", EMERGENCY STOP" : "",
              s.has_state_bit(shm::state_bits::kAwaitingOperator)
                  ? ", restarted after a fault: awaiting the operator's power-on"
                  : "",
              static_cast<unsigned long long>(s.vp.cycle), p[0], p[1], p[2],
              s.client_connected() ? "connected" : "not connected");
}

/// Sends a ctrl command and waits until the state shows its effect.
/// `effect` completes "the controller did not ..."; `done_text` is printed on success.
int command(hmi::Operator& op, shm::CtrlCode code, const char* effect, const char* done_text,
            bool (*done)(const ControllerStatus&), const hmi::HmiOptions& o) {
  if (!op.send_and_wait(code, done, o.timeout)) {
    const ControllerStatus s = op.status();
    std::fprintf(stderr, "hapticctrl-hmi: sent, but the controller did not %s within %lld ms%s\n",
                 effect, static_cast<long long>(o.timeout.count()),
                 s.emergency_stop() ? " (the emergency stop is latched: reset it first)" : "");
    return 1;
  }
  std::printf("%s\n", done_text);
  return 0;
}

int stop_controller(hmi::Operator& op, const hmi::HmiOptions& o) {
  op.send(shm::CtrlCode::kStop);
  const auto deadline = hapticctrl::MonotonicClock::now() + o.timeout + std::chrono::seconds(3);
  while (op.controller_alive() && hapticctrl::MonotonicClock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (op.controller_alive()) {
    std::fprintf(stderr,
                 "hapticctrl-hmi: the controller is still running after the stop request\n");
    return 1;
  }
  // The mapping outlives the removed segment: its last VP says how the controller ended.
  const ControllerStatus last = op.status();
  std::printf("controller '%s' stopped (%s, %s)\n", o.instance.c_str(),
              shm::core_state_name(last.vp.core_state), shm::stop_reason_name(last.vp.stop_reason));
  return 0;
}

int set_force(hmi::Operator& op, const shm::Vector6& wrench) {
  if (!op.force_available()) {
    std::fprintf(stderr, "hapticctrl-hmi: %s\n", op.force_unavailable().c_str());
    return 1;
  }
  if (!op.request_force(wrench)) {
    std::fprintf(stderr,
                 "hapticctrl-hmi: force refused: each force within +-%.0f N, torque +-%.0f N.m\n",
                 op.force().limits().max_force, op.force().limits().max_torque);
    return 1;
  }
  op.settle_force();
  const auto& w = op.force().applied();
  std::printf("operator wrench %.3f %.3f %.3f N %.3f %.3f %.3f N.m\n", w[0], w[1], w[2], w[3], w[4],
              w[5]);
  return 0;
}

int play(hmi::Operator& op, const hmi::HmiOptions& o) {
  const hmi::WrenchSequence sequence = hmi::WrenchSequence::load(o.sequence_path);
  if (o.power_on && command(
                        op, shm::CtrlCode::kPowerOn, "power on", "powered on",
                        [](const ControllerStatus& s) { return s.powered(); }, o) != 0) {
    return 1;
  }
  std::ofstream file;
  if (o.log_path != "-") {
    file.open(o.log_path);
    if (!file) {
      throw hmi::HmiError("cannot write the log '" + o.log_path + "'");
    }
  }
  std::ostream& log = o.log_path == "-" ? std::cout : file;
  std::fprintf(stderr, "hapticctrl-hmi: playing %zu samples over %.3f s\n",
               sequence.samples().size(), sequence.duration());
  const hmi::PlayResult r = hmi::play_sequence(
      op, sequence, log, o.with_hand ? std::optional<hmi::HandOptions>(o.hand) : std::nullopt);
  std::fprintf(stderr, "hapticctrl-hmi: played %.3f s of %zu samples, %llu cycles logged to %s%s\n",
               r.played_s, sequence.samples().size(), static_cast<unsigned long long>(r.rows),
               o.log_path == "-" ? "stdout" : o.log_path.c_str(),
               r.controller_stopped ? "; the controller stopped during playback" : "");
  return r.controller_stopped ? 1 : 0;
}

/// Exit status of a panel whose operator asked for a new controller (EX_TEMPFAIL).
constexpr int kRestartRequested = 75;

/// The panel, re-attached to each new controller of the instance until the operator quits.
int panel_session(const hmi::HmiOptions& o) {
  std::optional<hmi::Operator> op;
  op.emplace(o.instance, true);
  for (;;) {
    switch (hmi::run_panel(*op, o.offer_restart)) {
      case hmi::PanelEnd::kQuit:
        return 0;
      case hmi::PanelEnd::kRestartRequested:
        return kRestartRequested;
      case hmi::PanelEnd::kControllerReplaced:
        op.reset();
        op.emplace(o.instance, true);
        break;
    }
  }
}

int run(const hmi::HmiOptions& o) {
  if (o.command == HmiCommand::kPanel) {
    return panel_session(o);
  }
  hmi::Operator op(o.instance, needs_force(o.command));
  switch (o.command) {
    case HmiCommand::kPanel:
      return 1;  // handled above
    case HmiCommand::kStatus:
      print_status(op.status(), o.json);
      return 0;
    case HmiCommand::kPowerOn:
      return command(
          op, shm::CtrlCode::kPowerOn, "power on", "powered on",
          [](const ControllerStatus& s) { return s.powered(); }, o);
    case HmiCommand::kPowerOff:
      return command(
          op, shm::CtrlCode::kPowerOff, "power off", "powered off",
          [](const ControllerStatus& s) { return !s.powered(); }, o);
    case HmiCommand::kEmergencyStop:
      return command(
          op, shm::CtrlCode::kEmergencyStop, "latch the emergency stop", "emergency stop latched",
          [](const ControllerStatus& s) { return s.emergency_stop(); }, o);
    case HmiCommand::kEmergencyReset:
      return command(
          op, shm::CtrlCode::kEmergencyReset, "reset the emergency stop", "emergency stop reset",
          [](const ControllerStatus& s) { return !s.emergency_stop(); }, o);
    case HmiCommand::kStop:
      return stop_controller(op, o);
    case HmiCommand::kForce:
      return set_force(op, o.wrench);
    case HmiCommand::kZeroForce:
      op.release_hand();  // a hand a killed `play --hand` left gripping
      return set_force(op, {});
    case HmiCommand::kPlay:
      return play(op, o);
  }
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<hmi::HmiOptions>(
      "hapticctrl-hmi", argc, argv,
      [](const std::vector<std::string>& args, hmi::HmiOptions& c) {
        c = hmi::HmiOptions::parse(args);
        return !c.help;
      },
      &hmi::HmiOptions::usage, [](const hmi::HmiOptions& c) { return run(c); });
}
