// Cross-process torture of the seqlock: real processes, a MAP_SHARED mapping, checksummed
// payloads. (Threads-only semantics live in seqlock_test.cpp.)
#include <sys/mman.h>

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <new>
#include <random>

#include "hapticctrl/shm/seqlock.hpp"
#include "support/child_process.hpp"

namespace hapticctrl::shm {
namespace {

using namespace std::chrono_literals;
using test::Child;
using test::ReadyPipe;

struct Checked {
  std::uint64_t counter = 0;
  std::array<std::uint64_t, 34> body{};  // a VP-sized payload (288 bytes)
  std::uint64_t checksum = 0;

  static Checked make(std::uint64_t counter) {
    Checked c;
    c.counter = counter;
    for (std::size_t i = 0; i < c.body.size(); ++i) {
      c.body[i] = (counter + i) * 0x9E3779B97F4A7C15ULL;
    }
    c.checksum = c.sum();
    return c;
  }
  [[nodiscard]] std::uint64_t sum() const {
    std::uint64_t s = counter;
    for (const auto w : body) {
      s = (s ^ w) * 0x100000001B3ULL;
    }
    return s;
  }
};
static_assert(sizeof(Checked) == 288);

/// A seqlock cell in an anonymous shared mapping inherited by forked children.
class SharedCell {
 public:
  SharedCell() {
    memory_ = mmap(nullptr, sizeof(SeqlockCell<Checked>), PROT_READ | PROT_WRITE,
                   MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory_ == MAP_FAILED) {
      throw std::runtime_error("mmap failed");
    }
    cell_ = new (memory_) SeqlockCell<Checked>();
  }
  SharedCell(const SharedCell&) = delete;
  SharedCell& operator=(const SharedCell&) = delete;
  ~SharedCell() { munmap(memory_, sizeof(SeqlockCell<Checked>)); }
  SeqlockCell<Checked>& cell() { return *cell_; }

 private:
  void* memory_ = nullptr;
  SeqlockCell<Checked>* cell_ = nullptr;
};

int run_writer_forever(SeqlockCell<Checked>& cell, ReadyPipe& ready) {
  cell.publish_quietly(Checked::make(1), 1);
  ready.signal();
  for (std::uint64_t n = 2;; ++n) {
    cell.publish_quietly(Checked::make(n), static_cast<std::int64_t>(n));
  }
}

/// Reads until `target` consistent snapshots were checked (bounded by 50x as many attempts).
/// Exit codes: 0 ok, 2 a torn payload was accepted, 3 sequence went back, 4 too few good reads.
int run_reader(const SeqlockCell<Checked>& cell, std::uint64_t target) {
  Checked out;
  std::uint64_t last = 0;
  std::uint64_t good = 0;
  for (std::uint64_t attempt = 0; attempt < 50 * target && good < target; ++attempt) {
    const ReadResult r = cell.read(out);
    if (!r.ok()) {
      continue;
    }
    ++good;
    if (out.checksum != out.sum() || out.counter != r.sequence) {
      return 2;
    }
    if (r.sequence < last) {
      return 3;
    }
    last = r.sequence;
  }
  return good >= target ? 0 : 4;
}

TEST(SeqlockMultiprocess, MillionReadsInOtherProcessesAcceptNoTornPayload) {
  SharedCell shared;
  ReadyPipe ready;
  Child writer([&] { return run_writer_forever(shared.cell(), ready); });
  ASSERT_EQ(ready.wait(), 'r');
#ifdef HAPTICCTRL_SANITIZED
  constexpr std::uint64_t kReadsPerReader = 100'000;  // instrumented atomics are ~30x slower
#else
  constexpr std::uint64_t kReadsPerReader = 1'000'000;
#endif
  Child reader_a([&] { return run_reader(shared.cell(), kReadsPerReader); });
  Child reader_b([&] { return run_reader(shared.cell(), kReadsPerReader); });
  EXPECT_EQ(reader_a.wait(120s), 0);
  EXPECT_EQ(reader_b.wait(120s), 0);
  writer.kill_now();
  EXPECT_EQ(writer.wait(), 128 + SIGKILL);
  EXPECT_GT(shared.cell().publish_count(), 1U) << "the writer really ran";
}

TEST(SeqlockMultiprocess, WriterStoppedMidWriteCannotHangReaders) {
  SharedCell shared;
  ReadyPipe ready;
  Child writer([&] {
    shared.cell().publish_quietly(Checked::make(1), 1);
    shared.cell().raw_sequence_word().fetch_add(1);  // begin a write ...
    ready.signal();
    pause();  // ... and never finish it
    return 0;
  });
  ASSERT_EQ(ready.wait(), 'r');
  writer.kill_now();
  ASSERT_EQ(writer.wait(), 128 + SIGKILL);

  Checked out;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(shared.cell().read(out).status, ReadStatus::kTorn);
  EXPECT_EQ(shared.cell().wait_for_publish(shared.cell().sequence_word(), 20ms),
            WaitStatus::kTimedOut);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 2s);
}

TEST(SeqlockMultiprocess, WriterKilledAtRandomMomentsLeavesReadsBounded) {
  std::mt19937 rng(20261122);
  std::uniform_int_distribution<int> delay_us(50, 3000);
  int torn_seen = 0;
  for (int round = 0; round < 20; ++round) {
    SharedCell shared;
    ReadyPipe ready;
    Child writer([&] { return run_writer_forever(shared.cell(), ready); });
    ASSERT_EQ(ready.wait(), 'r');
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    writer.kill_now();
    ASSERT_EQ(writer.wait(), 128 + SIGKILL);
    Checked out;
    const auto start = std::chrono::steady_clock::now();
    const ReadResult r = shared.cell().read(out);
    EXPECT_LT(std::chrono::steady_clock::now() - start, 1s);
    if (r.ok()) {
      EXPECT_EQ(out.checksum, out.sum()) << "round " << round;
    } else {
      EXPECT_EQ(r.status, ReadStatus::kTorn);
      ++torn_seen;
    }
  }
  RecordProperty("killed_mid_write", torn_seen);
}

}  // namespace
}  // namespace hapticctrl::shm
