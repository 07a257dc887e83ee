// LCM over UDP multicast with ttl=0 (the telemetry bus of hapticctrl-lcm): the message published
// as raw bytes on a channel of this run's own; the reader handles what arrived and keeps the
// newest (LCM queues, it has no latest value).
#include <poll.h>
#include <unistd.h>

#include <cstring>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>

#include "hapticctrl/lcmtypes/channels.hpp"
#include "peers/peer_transport.hpp"

namespace hapticctrl::bench {
namespace {

class LcmWriter final : public PeerWriter {
 public:
  explicit LcmWriter(std::string channel)
      : lcm_(lcmtypes::kDefaultLcmUrl), channel_(std::move(channel)) {
    if (!lcm_.good()) {
      throw std::runtime_error("lcm: no multicast on loopback (see docs/lcm.md)");
    }
  }
  bool publish(const Message& message) override {
    return lcm_.publish(channel_, &message, sizeof message) == 0;
  }

 private:
  lcm::LCM lcm_;
  std::string channel_;
};

class LcmReader final : public PeerReader {
 public:
  explicit LcmReader(const std::string& channel) : lcm_(lcmtypes::kDefaultLcmUrl) {
    if (!lcm_.good()) {
      throw std::runtime_error("lcm: no multicast on loopback (see docs/lcm.md)");
    }
    lcm_.subscribe(channel, &LcmReader::on_message, this);
  }
  bool wait(std::chrono::milliseconds timeout) override {
    pollfd p{lcm_.getFileno(), POLLIN, 0};
    return poll(&p, 1, static_cast<int>(timeout.count())) > 0;
  }
  bool read(Message& out) override {
    got_ = false;
    pollfd p{lcm_.getFileno(), POLLIN, 0};
    while (poll(&p, 1, 0) > 0 && lcm_.handle() == 0) {
    }
    if (got_) {
      out = newest_;
    }
    return got_;
  }

 private:
  void on_message(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    if (buffer->data_size == sizeof newest_) {
      std::memcpy(&newest_, buffer->data, sizeof newest_);
      got_ = true;
    }
  }

  lcm::LCM lcm_;
  Message newest_{};
  bool got_ = false;
};

class LcmTransport final : public PeerTransport {
 public:
  [[nodiscard]] std::string name() const override { return "lcm"; }
  [[nodiscard]] std::vector<ReadMode> modes() const override { return {ReadMode::kWake}; }
  void setup(ReadMode /*mode*/) override {
    channel_ = "HC_PEER_BENCH_" + std::to_string(getpid()) + "_" + std::to_string(++runs_);
  }
  std::unique_ptr<PeerWriter> make_writer(ReadMode /*mode*/) override {
    return std::make_unique<LcmWriter>(channel_);
  }
  std::unique_ptr<PeerReader> make_reader(ReadMode /*mode*/) override {
    return std::make_unique<LcmReader>(channel_);
  }

 private:
  std::string channel_;
  int runs_ = 0;
};

}  // namespace

std::unique_ptr<PeerTransport> make_lcm_transport() {
  return std::make_unique<LcmTransport>();
}

}  // namespace hapticctrl::bench
