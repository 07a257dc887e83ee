#pragma once
/// @file messages.hpp
/// The controller's regions as ROS 2 messages (ros2types/): each message is filled in place, its
/// strings and sequences pointing at storage the holder owns, so a publish allocates nothing
/// (Cyclone DDS serialises straight from them). Stamps are the controller's own: the time the
/// core published the sample (CLOCK_MONOTONIC of its host), never the bridge's.
///
/// Real-time contract: constructors allocate (setup); every fill() is noexcept and
/// allocation-free (the publisher thread, soft-RT).
#include <array>
#include <cstdint>
#include <string>

#include "hapticctrl/shm/payloads.hpp"
#include "ros2_messages.h"

namespace hapticctrl::dds_bridge {

/// Handle pose, rendered and operator wrenches and joint states of one Position sample.
class ArmMessages {
 public:
  explicit ArmMessages(std::string frame);
  ArmMessages(const ArmMessages&) = delete;
  ArmMessages& operator=(const ArmMessages&) = delete;
  ArmMessages(ArmMessages&&) = delete;
  ArmMessages& operator=(ArmMessages&&) = delete;
  ~ArmMessages() = default;

  void fill(const shm::PositionPayload& p, std::int64_t stamp_ns) noexcept;

  geometry_msgs_msg_dds__PoseStamped_ pose{};
  geometry_msgs_msg_dds__WrenchStamped_ rendered_wrench{};  ///< the coupling wrench, base frame
  geometry_msgs_msg_dds__WrenchStamped_ operator_wrench{};  ///< the operator's, base frame
  sensor_msgs_msg_dds__JointState_ joints{};

 private:
  std::string frame_;
  std::array<double, 6> position_{};
  std::array<double, 6> velocity_{};
  std::array<double, 6> effort_{};
  std::array<char*, 6> names_{};
};

/// The controller's state and cycle statistics as one diagnostic_msgs/DiagnosticStatus:
/// level OK while running with no deadline miss in the recent window, WARN with misses, ERROR in
/// fail-safe, STALE once the controller stopped or went away.
class DiagnosticsMessage {
 public:
  /// `name` and `hardware_id` as the status carries them ("hapticctrl-core", the instance).
  DiagnosticsMessage(std::string name, std::string hardware_id, std::string frame);
  DiagnosticsMessage(const DiagnosticsMessage&) = delete;
  DiagnosticsMessage& operator=(const DiagnosticsMessage&) = delete;
  DiagnosticsMessage(DiagnosticsMessage&&) = delete;
  DiagnosticsMessage& operator=(DiagnosticsMessage&&) = delete;
  ~DiagnosticsMessage() = default;

  /// `core_present`: false once the controller is gone (STALE whatever the region says).
  void fill(const shm::TelemetryPayload& t, bool core_present, std::int64_t stamp_ns) noexcept;

  diagnostic_msgs_msg_dds__DiagnosticArray_ array{};

  static constexpr std::size_t kValues = 14;

 private:
  void set(std::size_t i, double v, int decimals) noexcept;

  std::string frame_;
  std::string name_;
  std::string hardware_id_;
  std::array<char, 96> message_{};
  diagnostic_msgs_msg_dds__DiagnosticStatus_ status_{};
  std::array<diagnostic_msgs_msg_dds__KeyValue_, kValues> values_{};
  std::array<std::array<char, 48>, kValues> texts_{};
};

/// The diagnostic levels of diagnostic_msgs/DiagnosticStatus.
enum class DiagnosticLevel : std::uint8_t { kOk = 0, kWarn = 1, kError = 2, kStale = 3 };

}  // namespace hapticctrl::dds_bridge
