// Connection's parameter calls: each one PARAM, sent reliably through the I/O shell
// (connection_impl.hpp) and acknowledged by the controller, or a ClientError.
#include <algorithm>
#include <array>
#include <limits>

#include "connection_impl.hpp"
#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::client {

namespace {
/// The first protocol version with the _SP frame parameters.
constexpr std::uint32_t kSinglePrecisionFrames = protocol::make_version(1, 2);

hcp_param param_of(hcp_param_id id) {
  hcp_param p{};
  p.id = id;
  return p;
}
}  // namespace

void Connection::set_time_step(double seconds) {
  hcp_param p = param_of(HCP_P_TIME_STEP);
  p.hcp_param_u.time_step = seconds;
  impl_->set_param(p, "set_time_step");
}
void Connection::set_force_factor(double factor) {
  hcp_param p = param_of(HCP_P_FORCE_FACTOR);
  p.hcp_param_u.force_factor = factor;
  impl_->set_param(p, "set_force_factor");
}
void Connection::set_speed_factor(double factor) {
  hcp_param p = param_of(HCP_P_SPEED_FACTOR);
  p.hcp_param_u.speed_factor = factor;
  impl_->set_param(p, "set_speed_factor");
}
// A 1.2 controller gets frames in single precision (PARAM 68 bytes, within the 90 of control
// frames); a 1.1 one the double form it knows (96 bytes).
void Connection::set_base_frame(const Pose7& frame) {
  hcp_param p{};
  if (controller_version() >= kSinglePrecisionFrames) {
    p = param_of(HCP_P_BASE_FRAME_SP);
    protocol::to_wire(frame, p.hcp_param_u.base_frame_sp);
  } else {
    p = param_of(HCP_P_BASE_FRAME);
    protocol::to_wire(frame, p.hcp_param_u.base_frame);
  }
  impl_->set_param(p, "set_base_frame");
}
void Connection::set_observation_frame(const Pose7& frame) {
  hcp_param p{};
  if (controller_version() >= kSinglePrecisionFrames) {
    p = param_of(HCP_P_OBSERVATION_FRAME_SP);
    protocol::to_wire(frame, p.hcp_param_u.observation_frame_sp);
  } else {
    p = param_of(HCP_P_OBSERVATION_FRAME);
    protocol::to_wire(frame, p.hcp_param_u.observation_frame);
  }
  impl_->set_param(p, "set_observation_frame");
}
void Connection::set_indexing_mode(IndexingMode mode) {
  hcp_param p = param_of(HCP_P_INDEXING_MODE);
  p.hcp_param_u.indexing_mode = static_cast<std::uint32_t>(mode);
  impl_->set_param(p, "set_indexing_mode");
}
void Connection::set_command_type(CommandType type) {
  hcp_param p = param_of(HCP_P_COMMAND_TYPE);
  p.hcp_param_u.command_type = static_cast<std::uint32_t>(type);
  impl_->set_param(p, "set_command_type");
}
void Connection::attach_object(double mass, const std::array<double, 3>& inertia) {
  hcp_param p = param_of(HCP_P_OBJECT);
  p.hcp_param_u.object.attached = 1;
  p.hcp_param_u.object.mass = mass;
  protocol::to_wire(inertia, p.hcp_param_u.object.inertia);
  impl_->set_param(p, "attach_object");
}
void Connection::detach_object() {
  impl_->set_param(param_of(HCP_P_OBJECT), "detach_object");
}
void Connection::set_gains(double k_lin, double b_lin, double k_ang, double b_ang) {
  hcp_param p = param_of(HCP_P_GAINS);
  protocol::to_wire(std::array<double, 4>{k_lin, b_lin, k_ang, b_ang}, p.hcp_param_u.gains);
  impl_->set_param(p, "set_gains");
}
void Connection::set_force_limits(double force, double torque) {
  hcp_param p = param_of(HCP_P_FORCE_LIMITS);
  protocol::to_wire(std::array<double, 2>{force, torque}, p.hcp_param_u.force_limits);
  impl_->set_param(p, "set_force_limits");
}
void Connection::set_watchdog(std::chrono::milliseconds timeout) {
  hcp_param p = param_of(HCP_P_WATCHDOG);
  p.hcp_param_u.watchdog_ms = static_cast<std::uint32_t>(
      std::clamp<std::int64_t>(timeout.count(), 0, std::numeric_limits<std::uint32_t>::max()));
  impl_->set_param(p, "set_watchdog");
}
void Connection::set_power(bool on) {
  hcp_param p = param_of(HCP_P_POWER);
  p.hcp_param_u.power_on = on ? 1 : 0;
  impl_->set_param(p, "set_power");
}
void Connection::emergency_stop() {
  impl_->set_param(param_of(HCP_P_EMERGENCY_STOP), "emergency_stop");
}
void Connection::reset_emergency_stop() {
  impl_->set_param(param_of(HCP_P_EMERGENCY_RESET), "reset_emergency_stop");
}

}  // namespace hapticctrl::client
