// DDS (Cyclone DDS, the middleware of hapticctrl-dds) on loopback: the message's bytes written as
// one sample with ROS 2's sensor-data QoS (best effort, keep last 5), as the bridge publishes;
// the reader waits on a read condition, takes what arrived and keeps the newest. Discovery stays
// on loopback (unicast to 127.0.0.1) in a domain of this run's own.
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "hapticctrl/ros2types/participant.hpp"
#include "hapticctrl/ros2types/qos.hpp"
#include "peer_sample.h"
#include "peers/peer_transport.hpp"

namespace hapticctrl::bench {
namespace {

constexpr const char* kLoopbackConfig =
    "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General>"
    "<Discovery><ParticipantIndex>auto</ParticipantIndex><Peers><Peer address=\"127.0.0.1\"/>"
    "</Peers></Discovery>";

class DdsWriter final : public PeerWriter {
 public:
  DdsWriter(std::uint32_t domain, const std::string& topic) : participant_(domain) {
    const ros2types::Qos qos = ros2types::sensor_data_qos();
    writer_ = participant_.writer(hapticctrl_bench_PeerSample_desc, topic, qos.get());
  }
  bool publish(const Message& message) override {
    std::memcpy(bytes_.data(), &message, sizeof message);
    const hapticctrl_bench_PeerSample sample{
        {sizeof message, sizeof message, bytes_.data(), false}};
    return dds_write(writer_, &sample) == 0;
  }

 private:
  ros2types::Participant participant_;
  dds_entity_t writer_ = 0;
  std::array<std::uint8_t, sizeof(Message)> bytes_{};
};

class DdsReader final : public PeerReader {
 public:
  DdsReader(std::uint32_t domain, const std::string& topic) : participant_(domain) {
    const ros2types::Qos qos = ros2types::sensor_data_qos();
    reader_ = participant_.reader(hapticctrl_bench_PeerSample_desc, topic, qos.get());
    waitset_ = participant_.waitset_for({reader_});
  }
  bool wait(std::chrono::milliseconds timeout) override {
    return dds_waitset_wait(waitset_, nullptr, 0, DDS_MSECS(timeout.count())) > 0;
  }
  bool read(Message& out) override {
    bool got = false;
    ros2types::take_each<hapticctrl_bench_PeerSample>(reader_, [&](const auto& s) {
      if (s.bytes._length == sizeof out) {
        std::memcpy(&out, s.bytes._buffer, sizeof out);
        got = true;
      }
    });
    return got;
  }

 private:
  ros2types::Participant participant_;
  dds_entity_t reader_ = 0;
  dds_entity_t waitset_ = 0;
};

class DdsTransport final : public PeerTransport {
 public:
  [[nodiscard]] std::string name() const override { return "dds"; }
  [[nodiscard]] std::vector<ReadMode> modes() const override { return {ReadMode::kWake}; }
  void setup(ReadMode /*mode*/) override {
    // Before the fork, in the parent, which never starts DDS itself: each child does, after it.
    setenv("CYCLONEDDS_URI", kLoopbackConfig, 1);  // NOLINT(concurrency-mt-unsafe): one thread
    domain_ = 101 + static_cast<std::uint32_t>(getpid()) % 100;
    topic_ = "hc_peer_bench_" + std::to_string(++runs_);
  }
  std::unique_ptr<PeerWriter> make_writer(ReadMode /*mode*/) override {
    return std::make_unique<DdsWriter>(domain_, topic_);
  }
  std::unique_ptr<PeerReader> make_reader(ReadMode /*mode*/) override {
    return std::make_unique<DdsReader>(domain_, topic_);
  }

 private:
  std::uint32_t domain_ = 0;
  std::string topic_;
  int runs_ = 0;
};

}  // namespace

std::unique_ptr<PeerTransport> make_dds_transport() {
  return std::make_unique<DdsTransport>();
}

}  // namespace hapticctrl::bench
