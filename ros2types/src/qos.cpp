// Implements qos.hpp: ROS 2's sensor-data and default QoS profiles.
#include "hapticctrl/ros2types/qos.hpp"

#include <new>

namespace hapticctrl::ros2types {
namespace {

Qos make_qos(dds_reliability_kind_t reliability, int32_t depth) {
  Qos qos(dds_create_qos());
  if (!qos) {
    throw std::bad_alloc();
  }
  dds_qset_reliability(qos.get(), reliability, DDS_MSECS(100));
  dds_qset_durability(qos.get(), DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, depth);
  return qos;
}

}  // namespace

Qos sensor_data_qos() {
  return make_qos(DDS_RELIABILITY_BEST_EFFORT, 5);
}

Qos command_qos() {
  return make_qos(DDS_RELIABILITY_RELIABLE, 10);
}

Qos discovery_qos() {
  Qos qos = make_qos(DDS_RELIABILITY_RELIABLE, 1);
  dds_qset_durability(qos.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  return qos;
}

}  // namespace hapticctrl::ros2types
