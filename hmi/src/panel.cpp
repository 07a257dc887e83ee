// Implements panel.hpp: the full-screen operator panel (ncurses).
#include "hapticctrl/hmi/panel.hpp"

#include <curses.h>
#include <unistd.h>

#include <array>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <deque>
#include <string>

#include "hapticctrl/hmi/panel_keys.hpp"
#include "hapticctrl/shm/events.hpp"
#include "hapticctrl/shm/names.hpp"

namespace hapticctrl::hmi {
namespace {

constexpr int kKeyPollMs = 2;                                 // force ramp ticks at up to 500 Hz
constexpr Duration kRedraw = std::chrono::milliseconds(100);  // 10 Hz: a human rate
constexpr std::size_t kEventLines = 6;
constexpr std::array<const char*, 6> kAxisNames{"fx", "fy", "fz", "tx", "ty", "tz"};
constexpr std::array<const char*, 5> kCommandTypes{"none", "IMPEDANCE", "VIRTMECH", "ARTICULAR",
                                                   "ARTICULAR_IMPEDANCE"};

/// One screen row, printf-style with the compiler checking the format (mvprintw is unchecked).
__attribute__((format(printf, 2, 3))) void line(int row, const char* format, ...) {
  char text[256];  // NOLINT(*-avoid-c-arrays)
  va_list args;    // NOLINT(*-vararg)
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  mvaddstr(row, 0, text);
  clrtoeol();
}

/// Text at (row, col), in reverse video when it is something the operator must notice.
void badge(int row, int col, const char* text, bool alert) {
  if (alert) {
    attron(A_REVERSE | A_BOLD);
  }
  mvaddstr(row, col, text);
  if (alert) {
    attroff(A_REVERSE | A_BOLD);
  }
}

double us(std::int64_t ns) {
  return static_cast<double>(ns) / 1000.0;
}

struct PanelView {
  std::deque<std::string> events;
  std::string message;
  ControllerStatus previous;
  double frames_per_cycle = -1.0;
};

void draw(const ControllerStatus& s, const PanelForce& force, const Operator& op,
          const PanelView& view) {
  const shm::PositionPayload& p = s.position;
  const shm::TelemetryPayload& t = s.telemetry;
  int row = 0;
  line(row++, "hapticctrl-hmi  '%s'  cycle %llu  period %.0f us  rt %s", s.instance.c_str(),
       static_cast<unsigned long long>(s.vp.cycle), us(t.period_ns), shm::rt_mode_name(t.rt_mode));
  ++row;
  move(row, 0);
  clrtoeol();
  badge(row, 0, s.powered() ? " POWER ON " : " power off ", s.powered());
  badge(row, 14, s.emergency_stop() ? " EMERGENCY STOP " : " e-stop clear ", s.emergency_stop());
  if (s.has_state_bit(shm::state_bits::kAwaitingOperator)) {
    badge(row, 32, " RESTARTED: p powers on (clients may not until then) ", true);
  }
  line(++row, "state %s   command %s%s%s", shm::core_state_name(s.vp.core_state),
       kCommandTypes[s.vp.command_type < kCommandTypes.size() ? s.vp.command_type : 0],
       s.has_state_bit(shm::state_bits::kCoupled) ? "   coupled" : "",
       s.has_state_bit(shm::state_bits::kDegraded) ? "   DEGRADED" : "");
  move(++row, 0);
  clrtoeol();
  if (s.has_state_bit(shm::state_bits::kFailSafe)) {
    const std::string text = std::string(" FAIL-SAFE: ") + shm::stop_reason_name(s.vp.stop_reason);
    badge(row, 0, text.c_str(), true);
  } else {
    mvaddstr(row, 0, "fail-safe: no");
  }
  row += 2;
  line(row++, "handle   x %+8.4f  y %+8.4f  z %+8.4f m   q %+6.3f %+6.3f %+6.3f %+6.3f",
       p.handle_pose[0], p.handle_pose[1], p.handle_pose[2], p.handle_pose[3], p.handle_pose[4],
       p.handle_pose[5], p.handle_pose[6]);
  constexpr double kDeg = 57.29577951308232;
  line(row++, "joints   %+7.2f %+7.2f %+7.2f %+7.2f %+7.2f %+7.2f deg", p.joint_position[0] * kDeg,
       p.joint_position[1] * kDeg, p.joint_position[2] * kDeg, p.joint_position[3] * kDeg,
       p.joint_position[4] * kDeg, p.joint_position[5] * kDeg);
  line(row++, "operator %+7.2f %+7.2f %+7.2f N  %+6.3f %+6.3f %+6.3f N.m", p.operator_wrench[0],
       p.operator_wrench[1], p.operator_wrench[2], p.operator_wrench[3], p.operator_wrench[4],
       p.operator_wrench[5]);
  line(row++, "coupling %+7.2f %+7.2f %+7.2f N  %+6.3f %+6.3f %+6.3f N.m", p.rendered_wrench[0],
       p.rendered_wrench[1], p.rendered_wrench[2], p.rendered_wrench[3], p.rendered_wrench[4],
       p.rendered_wrench[5]);
  ++row;
  line(row++, "cycle    wake p99 %.1f us (max %.1f)  servo p99 %.1f us", us(t.wake_latency.p99_ns),
       us(t.wake_latency.max_ns), us(t.servo_execution.p99_ns));
  line(row++, "         misses %llu (in a row %u)  degraded cycles %llu",
       static_cast<unsigned long long>(t.misses_total), t.consecutive_misses,
       static_cast<unsigned long long>(t.degraded_cycles));
  if (s.client_connected()) {
    const double loss =
        view.frames_per_cycle < 0 ? 0.0 : 100.0 * std::max(0.0, 1.0 - view.frames_per_cycle);
    line(row++, "client   port %u session %llu  age %.2f ms  frames/cycle %.3f (loss %.1f %%)%s",
         s.link.peer_port, static_cast<unsigned long long>(s.link.session_id), s.client_age_ms(),
         view.frames_per_cycle, loss,
         s.has_state_bit(shm::state_bits::kClientStale) ? "  STALE" : "");
  } else {
    line(row++, "client   not connected (watchdog expiries %llu)",
         static_cast<unsigned long long>(s.link.watchdog_expiries));
  }
  ++row;
  const shm::Vector6& applied = op.force().applied();
  if (op.force_available()) {
    line(row++, "force    %s step %.3g %s | %+.2f %+.2f %+.2f N %+.3f %+.3f %+.3f N.m",
         kAxisNames[force.axis], force.step(), force.axis < 3 ? "N" : "N.m", applied[0], applied[1],
         applied[2], applied[3], applied[4], applied[5]);
  } else {
    line(row++, "force    unavailable: %s", op.force_unavailable().c_str());
  }
  line(row++, "%s", "keys     p power on  o power off  space e-stop  r reset  S stop  q quit");
  line(row++, "%s", "         1-6 axis  + / - push  [ ] step  0 release the handle");
  ++row;
  line(row++, "events");
  for (const auto& e : view.events) {
    line(row++, "  %s", e.c_str());
  }
  for (std::size_t i = view.events.size(); i < kEventLines; ++i) {
    line(row++, "%s", "");
  }
  ++row;
  line(row, "%s", view.message.c_str());
  refresh();
}

/// Ends curses mode on every way out of the panel.
struct CursesSession {
  CursesSession() {
    initscr();
    cbreak();
    noecho();
    keypad(stdscr, TRUE);
    curs_set(0);
    timeout(kKeyPollMs);
  }
  ~CursesSession() { endwin(); }
  CursesSession(const CursesSession&) = delete;
  CursesSession& operator=(const CursesSession&) = delete;
};

void handle_command(Operator& op, shm::CtrlCode code, PanelView& view) {
  try {
    const ControllerStatus s = op.status();
    const std::uint32_t word = s.vp_ok ? s.vp.state_word : 0U;
    op.send(code);  // the core decides; the feedback says what to expect, and why not
    view.message = command_feedback(code, word);
  } catch (const HmiError& e) {
    view.message = e.what();
  }
}

/// The keyboard side of the panel: one key (or ERR for none). Returns false to quit.
class KeyHandler {
 public:
  explicit KeyHandler(Operator& op) : op_(&op), limits_(op.force().limits()) {
    force_.wrench = op.force().applied();
  }

  bool on_key(int key, PanelView& view) {
    if (asking_stop_) {
      return confirm_stop(key, view);
    }
    if (key == ERR) {
      return true;
    }
    const KeyResult r = apply_key(key, force_, limits_.max_force, limits_.max_torque);
    switch (r.action) {
      case PanelAction::kQuit:
        return false;
      case PanelAction::kCommand:
        handle_command(*op_, r.command, view);
        break;
      case PanelAction::kForce:
        view.message = op_->request_force(force_.wrench) ? "" : "force refused";
        break;
      case PanelAction::kAskStop:
        view.message = "stop the controller? press y to confirm";
        asking_stop_ = true;
        break;
      case PanelAction::kNone:
        break;
    }
    return true;
  }

  [[nodiscard]] const PanelForce& force() const noexcept { return force_; }

 private:
  bool confirm_stop(int key, PanelView& view) {
    if (key == ERR) {
      return true;  // still asking
    }
    asking_stop_ = false;
    if (key == 'y' || key == 'Y') {
      handle_command(*op_, shm::CtrlCode::kStop, view);
      view.message = "stop requested: the controller shuts down";
    } else {
      view.message = "stop cancelled";
    }
    return true;
  }

  Operator* op_;
  shm::ForceLimits limits_;
  PanelForce force_;
  bool asking_stop_ = false;
};

/// "controller failed safe: <reason> at 14:02:07" (or stopped, or lost), from the last VP.
std::string ending_banner(const ControllerStatus& last) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  std::array<char, 16> clock{};
  std::strftime(clock.data(), clock.size(), "%H:%M:%S", localtime_r(&now, &local));
  const bool failed = last.has_state_bit(shm::state_bits::kFailSafe) ||
                      last.vp.core_state == static_cast<std::uint32_t>(shm::CoreState::kFailSafe);
  const std::uint32_t reason = last.vp.stop_reason != 0
                                   ? last.vp.stop_reason
                                   : static_cast<std::uint32_t>(shm::StopReason::kCoreLost);
  return std::string(failed ? " controller failed safe: " : " controller stopped: ") +
         shm::stop_reason_name(reason) + " at " + clock.data() + " ";
}

/// Whether a controller of `instance` can be attached now (a new one after the last ended).
bool controller_available(const std::string& instance) {
  try {
    return shm::Segment::attach(instance).still_current();
  } catch (const shm::ShmError&) {
    return false;
  }
}

/// The screen once the controller has ended: why and when, in reverse video, until the operator
/// quits, asks for a new controller (offer_restart) or one appears (then the panel re-attaches).
PanelEnd wait_after_ending(const Operator& op, const PanelView& view, bool offer_restart) {
  const std::string banner = ending_banner(op.status());
  const std::string& instance = op.segment().instance();
  constexpr Duration kLookEvery = std::chrono::milliseconds(500);
  TimePoint next_look = MonotonicClock::now() + kLookEvery;
  erase();
  badge(0, 0, banner.c_str(), true);
  line(2, "%s", "the motors are off; a new controller starts powered off");
  line(3, offer_restart
              ? "keys     R start a new controller   q quit"
              : "keys     q quit   (the panel re-attaches to a controller started again)");
  int row = 5;
  line(row++, "last events");
  for (const auto& e : view.events) {
    line(row++, "  %s", e.c_str());
  }
  refresh();
  for (;;) {
    const int key = getch();
    if (key == 'q' || key == 'Q') {
      return PanelEnd::kQuit;
    }
    if (offer_restart && (key == 'R' || key == 'r')) {
      return PanelEnd::kRestartRequested;
    }
    if (MonotonicClock::now() >= next_look) {
      next_look += kLookEvery;
      if (controller_available(instance)) {
        return PanelEnd::kControllerReplaced;
      }
    }
  }
}

}  // namespace

PanelEnd run_panel(Operator& op, bool offer_restart) {
  if (isatty(STDIN_FILENO) == 0 || isatty(STDOUT_FILENO) == 0) {
    throw HmiError("the panel needs a terminal; without one use a command (status, power-on, ...)");
  }
  shm::EventReader events(op.segment().region<shm::RegionId::kEvents>(), /*from_start=*/true);
  PanelView view;
  KeyHandler keys(op);
  PanelEnd end = PanelEnd::kQuit;
  bool controller_gone = false;
  {
    CursesSession curses;
    TimePoint next_draw{};
    view.previous = op.status();
    while (keys.on_key(getch(), view)) {
      const TimePoint now = MonotonicClock::now();
      op.tick(now);
      if (now < next_draw) {
        continue;
      }
      next_draw = now + kRedraw;
      events.poll([&](const shm::Event& e) {
        view.events.push_back("cycle " + std::to_string(e.cycle) + ": " + shm::describe_event(e));
        if (view.events.size() > kEventLines) {
          view.events.pop_front();
        }
      });
      if (!op.controller_alive()) {  // after the events: the fail-safe's own is among them
        controller_gone = true;
        end = wait_after_ending(op, view, offer_restart);
        break;
      }
      const ControllerStatus s = op.status();
      view.frames_per_cycle = control_frames_per_cycle(view.previous, s);
      view.previous = s;
      draw(s, keys.force(), op, view);
    }
  }
  if (controller_gone) {
    // The mapping outlives the ended core: its last VP says how the controller ended.
    const ControllerStatus last = op.status();
    std::fprintf(stderr, "hapticctrl-hmi: the controller of instance '%s' ended (%s, %s)\n",
                 op.segment().instance().c_str(), shm::core_state_name(last.vp.core_state),
                 shm::stop_reason_name(last.vp.stop_reason));
    return end;
  }
  (void)op.request_force({});
  op.settle_force();  // let go of the handle before leaving
  return PanelEnd::kQuit;
}

}  // namespace hapticctrl::hmi
