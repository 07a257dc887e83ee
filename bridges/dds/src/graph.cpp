// Implements graph.hpp: the bridge's ParticipantEntitiesInfo on ros_discovery_info.
#include "hapticctrl/dds_bridge/graph.hpp"

#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/ros2types/qos.hpp"

namespace hapticctrl::dds_bridge {

namespace {

/// rmw_dds_common's names are string<=256: a longer one is refused, never cut.
template <std::size_t N>
void copy_bounded(const std::string& from, char (&to)[N], const char* what) {
  if (from.size() >= N) {
    throw std::invalid_argument(std::string(what) + " '" + from + "' is longer than " +
                                std::to_string(N - 1) + " characters (ROS 2's graph limit)");
  }
  std::memcpy(to, from.c_str(), from.size() + 1);
}

}  // namespace

rmw_dds_common_msg_dds__Gid_ gid_of(dds_entity_t entity) {
  dds_guid_t guid{};
  ros2types::checked(dds_get_guid(entity, &guid), "DDS entity GUID");
  rmw_dds_common_msg_dds__Gid_ gid{};
  static_assert(sizeof guid.v <= sizeof gid.data_);
  std::memcpy(gid.data_, guid.v, sizeof guid.v);
  return gid;
}

GraphAnnouncement::GraphAnnouncement(ros2types::Participant& participant,
                                     const Endpoints& endpoints, const std::string& ros_namespace) {
  const ros2types::Qos qos = ros2types::discovery_qos();
  writer_ = participant.writer(rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc,
                               std::string(ros2types::topic::kDiscoveryInfo), qos.get());
  std::array<rmw_dds_common_msg_dds__Gid_, 5> writers{
      gid_of(endpoints.handle_pose), gid_of(endpoints.rendered_wrench),
      gid_of(endpoints.operator_wrench), gid_of(endpoints.joint_states),
      gid_of(endpoints.diagnostics)};
  std::array<rmw_dds_common_msg_dds__Gid_, 2> readers{gid_of(endpoints.command),
                                                      gid_of(endpoints.operator_wrench_command)};
  rmw_dds_common_msg_dds__NodeEntitiesInfo_ node{};
  copy_bounded(ros_namespace, node.node_namespace_, "the ROS 2 namespace");
  copy_bounded(kNodeName, node.node_name_, "the node name");
  node.reader_gid_seq_._length = node.reader_gid_seq_._maximum = readers.size();
  node.reader_gid_seq_._buffer = readers.data();
  node.writer_gid_seq_._length = node.writer_gid_seq_._maximum = writers.size();
  node.writer_gid_seq_._buffer = writers.data();
  rmw_dds_common_msg_dds__ParticipantEntitiesInfo_ info{};
  info.gid_ = gid_of(participant.handle());
  info.node_entities_info_seq_._length = info.node_entities_info_seq_._maximum = 1;
  info.node_entities_info_seq_._buffer = &node;
  ros2types::checked(dds_write(writer_, &info), "ros_discovery_info");
}

}  // namespace hapticctrl::dds_bridge
