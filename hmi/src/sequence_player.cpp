// Implements sequence_player.hpp: plays a WrenchSequence as the operator force on the simulated
// handle and logs the arm's response, one CSV row per controller cycle (paced by the core's VP
// publishes).
#include "hapticctrl/hmi/sequence_player.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <optional>

namespace hapticctrl::hmi {
namespace {

template <std::size_t N>
void csv(std::ostream& out, const std::array<double, N>& values) {
  for (const double v : values) {
    out << ',' << v;
  }
}

void write_row(std::ostream& log, double t, const shm::Vector6& requested,
               const ControllerStatus& s, const shm::HandGrip& hand) {
  log << t << ',' << s.position.cycle << ',' << s.position.state_word;
  csv(log, requested);
  csv(log, s.position.operator_wrench);
  csv(log, s.position.handle_pose);
  csv(log, s.position.joint_position);
  csv(log, s.vp.object_wrench);
  csv(log, s.position.rendered_wrench);
  csv(log, hand.anchor);
  log << ',' << hand.stiffness << '\n';
}

std::array<double, 3> handle_point(const ControllerStatus& s) {
  return {s.position.handle_pose[0], s.position.handle_pose[1], s.position.handle_pose[2]};
}
std::array<double, 4> handle_rotation(const ControllerStatus& s) {
  const auto& p = s.position.handle_pose;
  const double n = std::sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5] + p[6] * p[6]);
  return n > 0.5 ? std::array<double, 4>{p[3] / n, p[4] / n, p[5] / n, p[6] / n}
                 : std::array<double, 4>{0, 0, 0, 1};
}

bool still_running(const ControllerStatus& s) {
  return s.vp_ok && s.vp.core_state == static_cast<std::uint32_t>(shm::CoreState::kRunning);
}

}  // namespace

const char* sequence_log_header() noexcept {
  return "t_s,cycle,state_word,req_fx,req_fy,req_fz,req_tx,req_ty,req_tz,"
         "op_fx,op_fy,op_fz,op_tx,op_ty,op_tz,x,y,z,qx,qy,qz,qw,"
         "q1,q2,q3,q4,q5,q6,cpl_fx,cpl_fy,cpl_fz,cpl_tx,cpl_ty,cpl_tz,"
         "ren_fx,ren_fy,ren_fz,ren_tx,ren_ty,ren_tz,hand_x,hand_y,hand_z,hand_k";
}

PlayResult play_sequence(Operator& op, const WrenchSequence& sequence, std::ostream& log,
                         const std::optional<HandOptions>& hand) {
  if (!op.force_available()) {
    throw HmiError("cannot play a sequence: " + op.force_unavailable());
  }
  std::optional<HandMotion> motion;
  if (hand) {
    const ControllerStatus s = op.status();
    if (!s.position_ok) {
      throw HmiError("cannot grip the handle: the controller publishes no position");
    }
    // Throws std::invalid_argument out of range.
    motion.emplace(*hand, handle_point(s), handle_rotation(s));
  }
  log << sequence_log_header() << '\n';
  PlayResult result;
  // Paced by VP, which the core publishes with a wake-up every cycle (position is published
  // quietly, without one), right after position.
  const auto& vp = op.segment().region<shm::RegionId::kVp>();
  const TimePoint start = MonotonicClock::now();
  const TimePoint end = start + from_seconds(sequence.duration());
  std::uint64_t last_cycle = 0;
  // The last pass plays the sequence's last sample: t is held at the end once it is reached (a
  // pass that began just before the end once stopped the player at 0.79997 s of 0.8, CI
  // 2026-12-02).
  for (bool last = false; !last;) {
    (void)vp.wait_for_publish(vp.sequence_word(), std::chrono::milliseconds(20));
    const TimePoint now = MonotonicClock::now();
    last = now >= end;
    const double t = last ? sequence.duration() : to_seconds(now - start);
    const shm::Vector6 requested = sequence.at(t);
    (void)op.request_force(requested);  // validated at load: cannot be refused
    if (motion) {
      (void)op.set_hand(motion->at(t));  // within the limits checked at construction
    }
    op.tick(now);
    const ControllerStatus s = op.status();
    if (!still_running(s)) {
      result.controller_stopped = true;
      break;
    }
    if (s.position_ok && s.position.cycle != last_cycle) {
      last_cycle = s.position.cycle;
      write_row(log, t, requested, s, op.hand());
      ++result.rows;
    }
    result.played_s = t;
  }
  if (!result.controller_stopped) {
    op.release_hand();
    (void)op.request_force({});
    op.settle_force();
  }
  log.flush();
  return result;
}

}  // namespace hapticctrl::hmi
