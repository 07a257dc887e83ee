// iceoryx 2.0 publish/subscribe (Debian's libiceoryx-posh), the reference zero-copy IPC: the
// writer loans a chunk, writes the message into it and publishes it; the reader keeps the latest
// value (a queue of one, oldest dropped) and either polls take() or blocks in a WaitSet. RouDi,
// iceoryx's broker, is started and stopped by the benchmark (peer_bench.cpp).
#include <unistd.h>

#include <stdexcept>
#include <string>

#include "iceoryx_hoofs/log/logmanager.hpp"
#include "iceoryx_posh/popo/publisher.hpp"
#include "iceoryx_posh/popo/subscriber.hpp"
#include "iceoryx_posh/popo/wait_set.hpp"
#include "iceoryx_posh/runtime/posh_runtime.hpp"
#include "peers/peer_transport.hpp"

namespace hapticctrl::bench {
namespace {

iox::capro::ServiceDescription service(int run) {
  const std::string instance = "run" + std::to_string(getppid()) + "_" + std::to_string(run);
  return {"hapticctrl", iox::capro::IdString_t(iox::cxx::TruncateToCapacity, instance), "vp"};
}

void init_runtime(const char* role) {
  // Its registration messages would drown the benchmark's own.
  iox::log::LogManager::GetLogManager().SetDefaultLogLevel(iox::log::LogLevel::kWarn);
  const std::string name = std::string("hc-peer-") + role + "-" + std::to_string(getpid());
  iox::runtime::PoshRuntime::initRuntime(iox::RuntimeName_t(iox::cxx::TruncateToCapacity, name));
}

iox::popo::PublisherOptions publisher_options() {
  iox::popo::PublisherOptions o;
  o.historyCapacity = 1;  // a late subscriber gets the latest value at once
  o.subscriberTooSlowPolicy = iox::popo::ConsumerTooSlowPolicy::DISCARD_OLDEST_DATA;
  return o;
}

iox::popo::SubscriberOptions subscriber_options() {
  iox::popo::SubscriberOptions o;
  o.queueCapacity = 1;  // the latest value, as a seqlock region holds it
  o.historyRequest = 1;
  o.queueFullPolicy = iox::popo::QueueFullPolicy::DISCARD_OLDEST_DATA;
  return o;
}

class IceoryxWriter final : public PeerWriter {
 public:
  explicit IceoryxWriter(int run)
      : publisher_((init_runtime("w"), service(run)), publisher_options()) {}
  bool publish(const Message& message) override {
    auto loaned = publisher_.loan();
    if (loaned.has_error()) {
      return false;
    }
    auto sample = std::move(loaned.value());
    *sample = message;
    sample.publish();
    return true;
  }

 private:
  iox::popo::Publisher<Message> publisher_;
};

class IceoryxReader final : public PeerReader {
 public:
  explicit IceoryxReader(int run)
      : subscriber_((init_runtime("r"), service(run)), subscriber_options()) {
    waitset_.attachState(subscriber_, iox::popo::SubscriberState::HAS_DATA).or_else([](auto&) {
      throw std::runtime_error("iceoryx: the WaitSet refused the subscriber");
    });
  }
  IceoryxReader(const IceoryxReader&) = delete;
  IceoryxReader& operator=(const IceoryxReader&) = delete;
  ~IceoryxReader() override {
    waitset_.detachState(subscriber_, iox::popo::SubscriberState::HAS_DATA);
  }
  bool wait(std::chrono::milliseconds timeout) override {
    return !waitset_.timedWait(iox::units::Duration::fromMilliseconds(timeout.count())).empty();
  }
  bool read(Message& out) override {
    bool got = false;
    for (;;) {
      auto taken = subscriber_.take();
      if (taken.has_error()) {
        return got;
      }
      out = *taken.value();
      got = true;
    }
  }

 private:
  iox::popo::Subscriber<Message> subscriber_;
  iox::popo::WaitSet<> waitset_;
};

class IceoryxTransport final : public PeerTransport {
 public:
  [[nodiscard]] std::string name() const override { return "iceoryx"; }
  [[nodiscard]] std::vector<ReadMode> modes() const override {
    return {ReadMode::kPoll, ReadMode::kWake};
  }
  void setup(ReadMode /*mode*/) override { ++run_; }
  std::unique_ptr<PeerWriter> make_writer(ReadMode /*mode*/) override {
    return std::make_unique<IceoryxWriter>(run_);
  }
  std::unique_ptr<PeerReader> make_reader(ReadMode /*mode*/) override {
    return std::make_unique<IceoryxReader>(run_);
  }

 private:
  int run_ = 0;
};

}  // namespace

std::unique_ptr<PeerTransport> make_iceoryx_transport() {
  return std::make_unique<IceoryxTransport>();
}

}  // namespace hapticctrl::bench
