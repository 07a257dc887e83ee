#pragma once
/* rosidl's form of the messages (rosidl_reference.idl): the descriptor of a C type name such as
 * "std_msgs_msg_dds__Header_", or NULL. */
#include "dds/dds.h"

#ifdef __cplusplus
extern "C" {
#endif
const dds_topic_descriptor_t* rosidl_reference(const char* c_type_name);
#ifdef __cplusplus
}
#endif
