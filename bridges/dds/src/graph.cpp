// Implements graph.hpp: the bridge's ParticipantEntitiesInfo on ros_discovery_info.
#include "hapticctrl/dds_bridge/graph.hpp"

#include <array>
#include <cstring>

#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/ros2types/qos.hpp"

namespace hapticctrl::dds_bridge {

rmw_dds_common_msg_dds__Gid_ gid_of(dds_entity_t entity) {
  dds_guid_t guid{};
  ros2types::checked(dds_get_guid(entity, &guid), "DDS entity GUID");
  rmw_dds_common_msg_dds__Gid_ gid{};
  static_assert(sizeof guid.v <= sizeof gid.data);
  std::memcpy(gid.data, guid.v, sizeof guid.v);
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
  std::string ns = ros_namespace;
  std::string name = kNodeName;
  rmw_dds_common_msg_dds__NodeEntitiesInfo_ node{};
  node.node_namespace = ns.data();
  node.node_name = name.data();
  node.reader_gid_seq._length = node.reader_gid_seq._maximum = readers.size();
  node.reader_gid_seq._buffer = readers.data();
  node.writer_gid_seq._length = node.writer_gid_seq._maximum = writers.size();
  node.writer_gid_seq._buffer = writers.data();
  rmw_dds_common_msg_dds__ParticipantEntitiesInfo_ info{};
  info.gid = gid_of(participant.handle());
  info.node_entities_info_seq._length = info.node_entities_info_seq._maximum = 1;
  info.node_entities_info_seq._buffer = &node;
  ros2types::checked(dds_write(writer_, &info), "ros_discovery_info");
}

}  // namespace hapticctrl::dds_bridge
