#pragma once
/// @file type_hash.hpp
/// REP-2011 type hashes of the ROS 2 messages the bridge has topics of, and the endpoint user
/// data that carries them (REP-2016 "typehash=RIHS01_<hex>;", as ROS 2 Iron and later write it):
/// computed at build time by ros2types/tools/type_hashes.py from the messages' definitions.
///
/// Real-time contract: setup only (not called from a cycle).
#include <string>
#include <string_view>

namespace hapticctrl::ros2types {

/// "RIHS01_<64 hex>" of the DDS type `dds_type` ("std_msgs::msg::dds_::String_"), or empty for a
/// type that has none here (rmw_dds_common's, which ROS 2 does not hash on the wire).
[[nodiscard]] std::string_view type_hash(std::string_view dds_type) noexcept;

/// The user data of an endpoint of `dds_type`: "typehash=RIHS01_<hex>;", or empty.
[[nodiscard]] std::string type_hash_user_data(std::string_view dds_type);

}  // namespace hapticctrl::ros2types
