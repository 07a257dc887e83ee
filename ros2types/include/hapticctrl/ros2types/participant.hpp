#pragma once
/// @file participant.hpp
/// One DDS domain participant and the writers and readers it owns, deleted with it. Discovery,
/// interfaces and transports come from Cyclone DDS's own configuration ($CYCLONEDDS_URI), as
/// for any ROS 2 node using rmw_cyclonedds_cpp. Setup code: allocates, throws
/// std::runtime_error naming what failed; writing and taking samples is the caller's (dds_write
/// and dds_take are safe from a soft-RT thread).
#include <dds/dds.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>

namespace hapticctrl::ros2types {

/// `rc` when it is a valid entity or a success; otherwise throws
/// std::runtime_error("<what>: <DDS's reason>").
dds_entity_t checked(dds_return_t rc, const std::string& what);

/// Calls `apply(const Message&)` for every sample with data waiting on `reader`, taking them
/// (DDS lends its own buffers, returned after each batch). Soft-RT safe: allocates nothing of its
/// own and never blocks.
template <typename Message, typename Apply>
void take_each(dds_entity_t reader, Apply apply) {
  constexpr std::size_t kBatch = 16;
  std::array<void*, kBatch> samples{};
  std::array<dds_sample_info_t, kBatch> infos{};
  for (;;) {
    samples.fill(nullptr);  // null: DDS lends its own buffers
    const dds_return_t n = dds_take(reader, samples.data(), infos.data(), kBatch, kBatch);
    if (n <= 0) {
      return;
    }
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      if (infos[i].valid_data) {
        apply(*static_cast<const Message*>(samples[i]));
      }
    }
    dds_return_loan(reader, samples.data(), n);
  }
}

class Participant {
 public:
  explicit Participant(std::uint32_t domain);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;
  Participant(Participant&&) = delete;
  Participant& operator=(Participant&&) = delete;

  /// A writer of `type` on DDS topic `topic` with `qos` (its topic gets the same QoS).
  dds_entity_t writer(const dds_topic_descriptor_t& type, const std::string& topic,
                      const dds_qos_t* qos);
  /// A reader of `type` on DDS topic `topic` with `qos`.
  dds_entity_t reader(const dds_topic_descriptor_t& type, const std::string& topic,
                      const dds_qos_t* qos);
  /// A waitset that wakes dds_waitset_wait() when any of `readers` holds a sample.
  dds_entity_t waitset_for(std::initializer_list<dds_entity_t> readers);
  [[nodiscard]] dds_entity_t handle() const noexcept { return participant_; }

 private:
  dds_entity_t topic(const dds_topic_descriptor_t& type, const std::string& name,
                     const dds_qos_t* qos);

  dds_entity_t participant_;
};

}  // namespace hapticctrl::ros2types
