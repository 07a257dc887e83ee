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
#define ROSIDL_TYPE(t) {#t, &t##_desc},
#include "rosidl_types.inc"
#undef ROSIDL_TYPE
};

const dds_topic_descriptor_t* rosidl_reference(const char* c_type_name) {
  for (size_t i = 0; i < sizeof kTable / sizeof kTable[0]; ++i) {
    if (strcmp(kTable[i].name, c_type_name) == 0) {
      return kTable[i].descriptor;
    }
  }
  return NULL;
}
