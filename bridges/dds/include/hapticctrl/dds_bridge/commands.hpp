#pragma once
/// @file commands.hpp
/// What comes in over DDS, decoded for shm::RemoteCommands (which applies the one rule of every
/// remote transport: the emergency stop always, the rest only with --allow-remote-commands).
///
/// Real-time contract: noexcept, allocation-free; the bridge's receive thread (soft-RT).
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "ros2_messages.h"

namespace hapticctrl::dds_bridge {

/// The command a std_msgs/String names: "power_on", "power_off", "emergency_stop",
/// "emergency_reset" or "stop", exactly; anything else (null included) is kNone.
[[nodiscard]] shm::CtrlCode command_of(const std_msgs_msg_dds__String_& message) noexcept;

/// The requested operator wrench (force then torque, base frame) of a WrenchStamped, as sent;
/// shm::RemoteCommands checks its values.
[[nodiscard]] shm::Vector6 wrench_of(const geometry_msgs_msg_dds__WrenchStamped_& message) noexcept;

}  // namespace hapticctrl::dds_bridge
