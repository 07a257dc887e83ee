// Implements messages.hpp: the controller's regions as ROS 2 messages, filled in place.
#include "hapticctrl/dds_bridge/messages.hpp"

#include <cstdio>

#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/shm/names.hpp"

namespace hapticctrl::dds_bridge {
namespace {

// The joint names of sensor_msgs/JointState; the namespace tells instances apart.
constexpr std::array<const char*, 6> kJointNames{"joint1", "joint2", "joint3",
                                                 "joint4", "joint5", "joint6"};
// The keys of the diagnostics values, in the order fill() sets them.
constexpr std::array<const char*, DiagnosticsMessage::kValues> kKeys{"core_state",
                                                                     "stop_reason",
                                                                     "rt_mode",
                                                                     "cycle",
                                                                     "period_us",
                                                                     "misses_total",
                                                                     "consecutive_misses",
                                                                     "window_miss_ppm",
                                                                     "wake_latency_p99_us",
                                                                     "servo_execution_p99_us",
                                                                     "servo_start_delay_p99_us",
                                                                     "degraded_cycles",
                                                                     "client_stale_cycles",
                                                                     "force_rejected"};

/// Points a message string at storage the holder owns. Cyclone's C types declare `char*`; a
/// write only reads it.
char* text(std::string& s) noexcept {
  return s.data();
}

void set_header(std_msgs_msg_dds__Header_& h, std::string& frame, std::int64_t stamp_ns) noexcept {
  h.stamp_ = ros2types::stamp_of(stamp_ns);
  h.frame_id_ = text(frame);
}

template <std::size_t N>
dds_sequence_double view(std::array<double, N>& values) noexcept {
  return {N, N, values.data(), false};
}

void set_wrench(geometry_msgs_msg_dds__Wrench_& w, const shm::Vector6& v) noexcept {
  w.force_ = {v[0], v[1], v[2]};
  w.torque_ = {v[3], v[4], v[5]};
}

DiagnosticLevel level_of(const shm::TelemetryPayload& t, bool core_present) noexcept {
  const auto state = static_cast<shm::CoreState>(t.core_state);
  if (!core_present || state == shm::CoreState::kStopped) {
    return DiagnosticLevel::kStale;
  }
  if (state == shm::CoreState::kFailSafe) {
    return DiagnosticLevel::kError;
  }
  return t.window_miss_ppm > 0 || t.consecutive_misses > 0 ? DiagnosticLevel::kWarn
                                                           : DiagnosticLevel::kOk;
}

double us(std::int64_t ns) noexcept {
  return static_cast<double>(ns) * 1e-3;
}

}  // namespace

ArmMessages::ArmMessages(std::string frame) : frame_(std::move(frame)) {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    names_[i] = const_cast<char*>(kJointNames[i]);  // NOLINT(*-const-cast): read by the write
  }
  joints.name_ = {6, 6, names_.data(), false};
  joints.position_ = view(position_);
  joints.velocity_ = view(velocity_);
  joints.effort_ = view(effort_);
}

void ArmMessages::fill(const shm::PositionPayload& p, std::int64_t stamp_ns) noexcept {
  set_header(pose.header_, frame_, stamp_ns);
  const auto& h = p.handle_pose;  // x y z, then the quaternion x y z w
  pose.pose_.position_ = {h[0], h[1], h[2]};
  pose.pose_.orientation_ = {h[3], h[4], h[5], h[6]};
  set_header(rendered_wrench.header_, frame_, stamp_ns);
  set_wrench(rendered_wrench.wrench_, p.rendered_wrench);
  set_header(operator_wrench.header_, frame_, stamp_ns);
  set_wrench(operator_wrench.wrench_, p.operator_wrench);
  set_header(joints.header_, frame_, stamp_ns);
  position_ = p.joint_position;
  velocity_ = p.joint_velocity;
  effort_ = p.joint_torque;
}

DiagnosticsMessage::DiagnosticsMessage(std::string name, std::string hardware_id, std::string frame)
    : frame_(std::move(frame)), name_(std::move(name)), hardware_id_(std::move(hardware_id)) {
  for (std::size_t i = 0; i < kValues; ++i) {
    values_[i].key_ = const_cast<char*>(kKeys[i]);  // NOLINT(*-const-cast): read by the write
    values_[i].value_ = texts_[i].data();
  }
  status_.name_ = text(name_);
  status_.hardware_id_ = text(hardware_id_);
  status_.message_ = message_.data();
  status_.values_ = {kValues, kValues, values_.data(), false};
  array.status_ = {1, 1, &status_, false};
}

void DiagnosticsMessage::set(std::size_t i, double v, int decimals) noexcept {
  std::snprintf(texts_[i].data(), texts_[i].size(), "%.*f", decimals, v);
}

void DiagnosticsMessage::fill(const shm::TelemetryPayload& t, bool core_present,
                              std::int64_t stamp_ns) noexcept {
  set_header(array.header_, frame_, stamp_ns);
  const DiagnosticLevel level = level_of(t, core_present);
  status_.level_ = static_cast<std::uint8_t>(level);
  const char* state = core_present ? shm::core_state_name(t.core_state) : "gone";
  if (t.stop_reason != 0) {
    std::snprintf(message_.data(), message_.size(), "%s: %s", state,
                  shm::stop_reason_name(t.stop_reason));
  } else {
    std::snprintf(message_.data(), message_.size(), "%s", state);
  }
  std::snprintf(texts_[0].data(), texts_[0].size(), "%s", state);
  std::snprintf(texts_[1].data(), texts_[1].size(), "%s", shm::stop_reason_name(t.stop_reason));
  std::snprintf(texts_[2].data(), texts_[2].size(), "%s", shm::rt_mode_name(t.rt_mode));
  set(3, static_cast<double>(t.cycle), 0);
  set(4, us(t.period_ns), 1);
  set(5, static_cast<double>(t.misses_total), 0);
  set(6, static_cast<double>(t.consecutive_misses), 0);
  set(7, static_cast<double>(t.window_miss_ppm), 0);
  set(8, us(t.wake_latency.p99_ns), 1);
  set(9, us(t.servo_execution.p99_ns), 1);
  set(10, us(t.servo_start_delay.p99_ns), 1);
  set(11, static_cast<double>(t.degraded_cycles), 0);
  set(12, static_cast<double>(t.vpr_stale), 0);
  set(13, static_cast<double>(t.force_rejected), 0);
}

}  // namespace hapticctrl::dds_bridge
