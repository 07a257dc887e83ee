// Implements endpoints.hpp: one instance's DDS writers and readers.
#include "hapticctrl/dds_bridge/endpoints.hpp"

#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/ros2types/qos.hpp"

namespace hapticctrl::dds_bridge {
namespace {

namespace topic = ros2types::topic;
using ros2types::dds_topic;

}  // namespace

Endpoints::Endpoints(ros2types::Participant& p, const std::string& ns) {
  const ros2types::Qos sensor = ros2types::sensor_data_qos();
  const ros2types::Qos commands = ros2types::command_qos();
  handle_pose = p.writer(geometry_msgs_msg_dds__PoseStamped__desc,
                         dds_topic(ns, topic::kHandlePose), sensor.get());
  rendered_wrench = p.writer(geometry_msgs_msg_dds__WrenchStamped__desc,
                             dds_topic(ns, topic::kRenderedWrench), sensor.get());
  operator_wrench = p.writer(geometry_msgs_msg_dds__WrenchStamped__desc,
                             dds_topic(ns, topic::kOperatorWrench), sensor.get());
  joint_states = p.writer(sensor_msgs_msg_dds__JointState__desc, dds_topic(ns, topic::kJointStates),
                          sensor.get());
  diagnostics = p.writer(diagnostic_msgs_msg_dds__DiagnosticArray__desc,
                         dds_topic(ns, topic::kDiagnostics), sensor.get());
  command =
      p.reader(std_msgs_msg_dds__String__desc, dds_topic(ns, topic::kCommand), commands.get());
  operator_wrench_command = p.reader(geometry_msgs_msg_dds__WrenchStamped__desc,
                                     dds_topic(ns, topic::kOperatorWrenchCommand), commands.get());
}

}  // namespace hapticctrl::dds_bridge
