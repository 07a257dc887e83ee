#pragma once
/// @file graph.hpp
/// The bridge as a node of ROS 2's graph (J6): the ParticipantEntitiesInfo that rmw implementations
/// publish on ros_discovery_info, naming the node and the GIDs of its writers and readers, so
/// that `ros2 node list`, `ros2 node info` and rqt_graph show hapticctrl's topics as the node's
/// instead of a bare DDS application's. Setup code: allocates, throws std::runtime_error.
#include <string>

#include "hapticctrl/dds_bridge/endpoints.hpp"
#include "hapticctrl/ros2types/participant.hpp"
#include "ros2_messages.h"

namespace hapticctrl::dds_bridge {

/// The node's name in ROS 2's graph.
inline constexpr const char* kNodeName = "hapticctrl_dds";

/// A GID as rmw_cyclonedds makes it: the entity's 16-byte GUID, zero-padded to 24 bytes.
[[nodiscard]] rmw_dds_common_msg_dds__Gid_ gid_of(dds_entity_t entity);

/// Announces the node `kNodeName` in `ros_namespace` with the endpoints' writers and readers, once
/// (transient local: later tools get it too); the announcement lasts as long as this object.
class GraphAnnouncement {
 public:
  GraphAnnouncement(ros2types::Participant& participant, const Endpoints& endpoints,
                    const std::string& ros_namespace);

 private:
  dds_entity_t writer_{};
};

}  // namespace hapticctrl::dds_bridge
