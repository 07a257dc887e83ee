/* The descriptors of rosidl_reference.idl by their C type name, in a translation unit of their
 * own: their C types have the names of ros2types' (the struct definitions would clash), and the
 * build renames their descriptors (CMakeLists.txt). */
#include "rosidl_reference_table.h"

#include <string.h>

#include "rosidl_reference.h"

static const struct {
  const char* name;
  const dds_topic_descriptor_t* descriptor;
} kTable[] = {
    {"builtin_interfaces_msg_dds__Time_", &builtin_interfaces_msg_dds__Time__desc},
    {"std_msgs_msg_dds__Header_", &std_msgs_msg_dds__Header__desc},
    {"std_msgs_msg_dds__String_", &std_msgs_msg_dds__String__desc},
    {"geometry_msgs_msg_dds__Point_", &geometry_msgs_msg_dds__Point__desc},
    {"geometry_msgs_msg_dds__Quaternion_", &geometry_msgs_msg_dds__Quaternion__desc},
    {"geometry_msgs_msg_dds__Vector3_", &geometry_msgs_msg_dds__Vector3__desc},
    {"geometry_msgs_msg_dds__Pose_", &geometry_msgs_msg_dds__Pose__desc},
    {"geometry_msgs_msg_dds__PoseStamped_", &geometry_msgs_msg_dds__PoseStamped__desc},
    {"geometry_msgs_msg_dds__Wrench_", &geometry_msgs_msg_dds__Wrench__desc},
    {"geometry_msgs_msg_dds__WrenchStamped_", &geometry_msgs_msg_dds__WrenchStamped__desc},
    {"sensor_msgs_msg_dds__JointState_", &sensor_msgs_msg_dds__JointState__desc},
    {"diagnostic_msgs_msg_dds__KeyValue_", &diagnostic_msgs_msg_dds__KeyValue__desc},
    {"diagnostic_msgs_msg_dds__DiagnosticStatus_",
     &diagnostic_msgs_msg_dds__DiagnosticStatus__desc},
    {"diagnostic_msgs_msg_dds__DiagnosticArray_", &diagnostic_msgs_msg_dds__DiagnosticArray__desc},
    {"rmw_dds_common_msg_dds__Gid_", &rmw_dds_common_msg_dds__Gid__desc},
    {"rmw_dds_common_msg_dds__NodeEntitiesInfo_", &rmw_dds_common_msg_dds__NodeEntitiesInfo__desc},
    {"rmw_dds_common_msg_dds__ParticipantEntitiesInfo_",
     &rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc},
};

const dds_topic_descriptor_t* rosidl_reference(const char* c_type_name) {
  for (size_t i = 0; i < sizeof kTable / sizeof kTable[0]; ++i) {
    if (strcmp(kTable[i].name, c_type_name) == 0) {
      return kTable[i].descriptor;
    }
  }
  return NULL;
}
