// The seqlock region as the core's VP is (shm/seqlock.hpp), in a shared mapping both processes
// inherit: polling reads of the latest value against a writer that publishes quietly, and a
// reader blocked on the futex against a writer that publishes with a wake-up.
#include <sys/mman.h>

#include <cerrno>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/shm/seqlock.hpp"
#include "peers/peer_transport.hpp"

namespace hapticctrl::bench {
namespace {

using Cell = shm::SeqlockCell<Message>;

class SeqlockWriter final : public PeerWriter {
 public:
  SeqlockWriter(Cell& cell, bool wake) : cell_(&cell), wake_(wake) {}
  bool publish(const Message& message) override {
    if (wake_) {
      cell_->publish(message, hapticctrl::to_ns(hapticctrl::MonotonicClock::now()));
    } else {
      cell_->publish_quietly(message, hapticctrl::to_ns(hapticctrl::MonotonicClock::now()));
    }
    return true;  // a seqlock publish cannot fail or wait
  }

 private:
  Cell* cell_;
  bool wake_;
};

class SeqlockReader final : public PeerReader {
 public:
  explicit SeqlockReader(const Cell& cell) : cell_(&cell), seen_(cell.sequence_word()) {}
  bool wait(std::chrono::milliseconds timeout) override {
    return cell_->wait_for_publish(seen_, timeout) == shm::WaitStatus::kPublished;
  }
  bool read(Message& out) override {
    seen_ = cell_->sequence_word();
    const shm::ReadResult r = cell_->read(out);
    if (!r.ok() || r.sequence == last_) {
      return false;
    }
    last_ = r.sequence;
    return true;
  }

 private:
  const Cell* cell_;
  std::uint32_t seen_;
  std::uint64_t last_ = 0;
};

class SeqlockTransport final : public PeerTransport {
 public:
  SeqlockTransport() = default;
  SeqlockTransport(const SeqlockTransport&) = delete;
  SeqlockTransport& operator=(const SeqlockTransport&) = delete;
  ~SeqlockTransport() override { teardown(); }

  [[nodiscard]] std::string name() const override { return "seqlock"; }
  [[nodiscard]] std::vector<ReadMode> modes() const override {
    return {ReadMode::kPoll, ReadMode::kWake};
  }
  void setup(ReadMode /*mode*/) override {
    void* at =
        mmap(nullptr, sizeof(Cell), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (at == MAP_FAILED) {
      throw std::runtime_error(std::string("seqlock: mmap: ") + std::strerror(errno));
    }
    cell_ = new (at) Cell();
  }
  std::unique_ptr<PeerWriter> make_writer(ReadMode mode) override {
    return std::make_unique<SeqlockWriter>(*cell_, mode == ReadMode::kWake);
  }
  std::unique_ptr<PeerReader> make_reader(ReadMode /*mode*/) override {
    return std::make_unique<SeqlockReader>(*cell_);
  }
  void teardown() override {
    if (cell_ != nullptr) {
      cell_->~Cell();
      munmap(cell_, sizeof(Cell));
      cell_ = nullptr;
    }
  }

 private:
  Cell* cell_ = nullptr;
};

}  // namespace

std::unique_ptr<PeerTransport> make_seqlock_transport() {
  return std::make_unique<SeqlockTransport>();
}

}  // namespace hapticctrl::bench
