// Implements participant.hpp: a DDS participant and its writers and readers.
#include "hapticctrl/ros2types/participant.hpp"

#include <stdexcept>
#include <string>

#include "hapticctrl/ros2types/qos.hpp"
#include "hapticctrl/ros2types/type_hash.hpp"

#ifdef HAPTICCTRL_TSAN
// ThreadSanitizer builds: Debian's Cyclone DDS is not instrumented, so TSan sees its own threads
// synchronise through interceptors (recvmsg, memcpy, pthread_mutex_lock) without seeing its
// atomics, and reports races inside libddsc (2026-12-02: ddsrt_recvmsg against a memcpy of the
// same receive buffer). Every program that creates a participant links this file: TSan ignores
// what libddsc's calls do, and still checks all of ours.
extern "C" const char* __tsan_default_suppressions() {  // NOLINT(*-reserved-identifier)
  return "called_from_lib:libddsc.so\n";
}
#endif

namespace hapticctrl::ros2types {

dds_entity_t checked(dds_return_t rc, const std::string& what) {
  if (rc < 0) {
    throw std::runtime_error(what + ": " + dds_strretcode(rc));
  }
  return rc;
}

Participant::Participant(std::uint32_t domain)
    : participant_(checked(
          dds_create_participant(domain, nullptr, nullptr),
          "DDS participant in domain " + std::to_string(domain) + " (see $CYCLONEDDS_URI)")) {}

Participant::~Participant() {
  dds_delete(participant_);
}

dds_entity_t Participant::topic(const dds_topic_descriptor_t& type, const std::string& name,
                                const dds_qos_t* qos) {
  return checked(dds_create_topic(participant_, &type, name.c_str(), qos, nullptr),
                 "DDS topic " + name);
}

namespace {

/// `qos` with the endpoint's user data "typehash=RIHS01_<hex>;" of `type` (REP-2016, as ROS 2
/// Iron and later set it; J6), where the type has a hash.
Qos with_type_hash(const dds_topic_descriptor_t& type, const dds_qos_t* qos) {
  Qos endpoint(dds_create_qos());
  if (qos != nullptr) {
    dds_copy_qos(endpoint.get(), qos);
  }
  const std::string user_data = type_hash_user_data(type.m_typename);
  if (!user_data.empty()) {
    dds_qset_userdata(endpoint.get(), user_data.data(), user_data.size());
  }
  return endpoint;
}

}  // namespace

dds_entity_t Participant::writer(const dds_topic_descriptor_t& type, const std::string& topic_name,
                                 const dds_qos_t* qos) {
  const Qos endpoint = with_type_hash(type, qos);
  return checked(
      dds_create_writer(participant_, topic(type, topic_name, qos), endpoint.get(), nullptr),
      "DDS writer on " + topic_name);
}

dds_entity_t Participant::reader(const dds_topic_descriptor_t& type, const std::string& topic_name,
                                 const dds_qos_t* qos) {
  const Qos endpoint = with_type_hash(type, qos);
  return checked(
      dds_create_reader(participant_, topic(type, topic_name, qos), endpoint.get(), nullptr),
      "DDS reader on " + topic_name);
}

dds_entity_t Participant::waitset_for(std::initializer_list<dds_entity_t> readers) {
  const dds_entity_t waitset = checked(dds_create_waitset(participant_), "DDS waitset");
  for (const dds_entity_t reader : readers) {
    const dds_entity_t condition =
        checked(dds_create_readcondition(reader, DDS_ANY_STATE), "DDS read condition");
    checked(dds_waitset_attach(waitset, condition, condition), "DDS waitset attach");
  }
  return waitset;
}

}  // namespace hapticctrl::ros2types
