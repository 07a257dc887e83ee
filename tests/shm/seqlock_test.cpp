// Tests of seqlock.hpp: a single-writer, multi-reader seqlock cell that lives in shared memory.
#include "hapticctrl/shm/seqlock.hpp"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace hapticctrl::shm {
namespace {

using namespace std::chrono_literals;

/// A payload that carries its own checksum, so a torn copy is detectable.
struct Checked {
  std::uint64_t counter = 0;
  std::array<std::uint64_t, 30> body{};
  std::uint64_t checksum = 0;

  static Checked make(std::uint64_t counter) {
    Checked c;
    c.counter = counter;
    for (std::size_t i = 0; i < c.body.size(); ++i) {
      c.body[i] = counter * 0x9E3779B97F4A7C15ULL + i;
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
  [[nodiscard]] bool intact() const { return checksum == sum(); }
};

TEST(Seqlock, NeverWrittenCellSaysSoAndLeavesOutputAlone) {
  SeqlockCell<Checked> cell;
  Checked out = Checked::make(7);
  const ReadResult r = cell.read(out);
  EXPECT_EQ(r.status, ReadStatus::kNeverWritten);
  EXPECT_EQ(out.counter, 7U);
  EXPECT_EQ(cell.publish_count(), 0U);
}

TEST(Seqlock, ReadReturnsLastPublishWithSequenceAndTimestamp) {
  SeqlockCell<Checked> cell;
  cell.publish_quietly(Checked::make(1), 1000);
  cell.publish_quietly(Checked::make(2), 2000);
  Checked out;
  const ReadResult r = cell.read(out);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(out.counter, 2U);
  EXPECT_TRUE(out.intact());
  EXPECT_EQ(r.sequence, 2U);
  EXPECT_EQ(r.publish_time_ns, 2000);
}

TEST(Seqlock, SequenceLetsReaderTellFreshStaleAndLost) {
  SeqlockCell<Checked> cell;
  Checked out;
  cell.publish_quietly(Checked::make(1), 1);
  const auto first = cell.read(out).sequence;
  EXPECT_EQ(cell.read(out).sequence, first);  // stale: same sample
  cell.publish_quietly(Checked::make(2), 2);
  cell.publish_quietly(Checked::make(3), 3);
  EXPECT_EQ(cell.read(out).sequence - first, 2U);  // one sample lost in between
}

TEST(Seqlock, TheSequenceWordWrapsWithoutLosingTheCell) {
  // 2^31 publishes bring the 32-bit word back to 0 (24.9 days at 1 kHz): forced here. A read
  // then reported kNeverWritten until 2026-12-04 (J4).
  SeqlockCell<Checked> cell;
  cell.publish_quietly(Checked::make(1), 1);
  cell.raw_sequence_word().store(0xFFFFFFFEU);  // the last even value before the wrap
  Checked out;
  ASSERT_TRUE(cell.read(out).ok());
  const std::uint32_t seen = cell.sequence_word();
  cell.publish(Checked::make(2), 2);  // 0xFFFFFFFF while it writes, then 0
  ASSERT_EQ(cell.sequence_word(), 0U) << "the word wrapped";
  EXPECT_EQ(cell.wait_for_publish(seen, 0ms), WaitStatus::kPublished);
  const ReadResult r = cell.read(out);
  ASSERT_EQ(r.status, ReadStatus::kOk);
  EXPECT_EQ(out.counter, 2U);
  EXPECT_TRUE(out.intact());
  EXPECT_EQ(r.sequence, 2U) << "the publish count goes on";
  cell.publish_quietly(Checked::make(3), 3);
  ASSERT_TRUE(cell.read(out).ok());
  EXPECT_EQ(out.counter, 3U);
}

TEST(Seqlock, WriteInProgressGivesTornAfterBoundedAttempts) {
  SeqlockCell<Checked> cell;
  cell.publish_quietly(Checked::make(1), 1);
  // Simulate a writer that died between its two sequence increments.
  cell.raw_sequence_word().fetch_add(1);
  Checked out = Checked::make(99);
  const ReadResult r = cell.read(out, 10);
  EXPECT_EQ(r.status, ReadStatus::kTorn);
  EXPECT_EQ(out.counter, 99U) << "a torn read must not touch the output";
}

TEST(Seqlock, WaitReturnsAtOnceWhenAPublishAlreadyHappened) {
  SeqlockCell<Checked> cell;
  const std::uint32_t seen = cell.sequence_word();
  cell.publish(Checked::make(1), 1);
  EXPECT_EQ(cell.wait_for_publish(seen, 1s), WaitStatus::kPublished);
}

TEST(Seqlock, WaitTimesOutWithoutPublish) {
  SeqlockCell<Checked> cell;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(cell.wait_for_publish(cell.sequence_word(), 20ms), WaitStatus::kTimedOut);
  EXPECT_GE(std::chrono::steady_clock::now() - start, 20ms);
}

TEST(Seqlock, WaitTimesOutOnWriterDeadMidWrite) {
  SeqlockCell<Checked> cell;
  cell.publish(Checked::make(1), 1);
  cell.raw_sequence_word().fetch_add(1);  // odd forever
  EXPECT_EQ(cell.wait_for_publish(cell.sequence_word(), 10ms), WaitStatus::kTimedOut);
}

TEST(Seqlock, BlockedReaderIsWokenByPublish) {
  SeqlockCell<Checked> cell;
  const std::uint32_t seen = cell.sequence_word();
  std::atomic<bool> woke{false};
  std::thread reader([&] { woke = cell.wait_for_publish(seen, 5s) == WaitStatus::kPublished; });
  std::this_thread::sleep_for(10ms);
  cell.publish(Checked::make(5), 5);
  reader.join();
  EXPECT_TRUE(woke.load());
}

// Runs under ThreadSanitizer in CI: one writer as fast as it can, several readers checking
// every snapshot's checksum and that sequences never go backwards.
TEST(Seqlock, ConcurrentReadersNeverSeeTornOrOlderPayloads) {
  auto cell = std::make_unique<SeqlockCell<Checked>>();
  std::atomic<bool> stop{false};
#ifdef HAPTICCTRL_SANITIZED
  constexpr std::uint64_t kReadsPerReader = 20'000;
#else
  constexpr std::uint64_t kReadsPerReader = 200'000;
#endif
  cell->publish_quietly(Checked::make(1), 1);  // readers must never race an empty cell here
  std::thread writer([&] {
    std::uint64_t n = 1;
    while (!stop.load(std::memory_order_relaxed)) {
      ++n;
      cell->publish_quietly(Checked::make(n), static_cast<std::int64_t>(n));
    }
  });
  std::atomic<std::uint64_t> corrupt{0};
  std::atomic<std::uint64_t> backwards{0};
  std::atomic<std::uint64_t> ok{0};
  std::vector<std::thread> readers;
  readers.reserve(3);
  for (int r = 0; r < 3; ++r) {
    readers.emplace_back([&] {
      std::uint64_t last = 0;
      Checked out;
      std::uint64_t good = 0;
      for (std::uint64_t i = 0; i < 50 * kReadsPerReader && good < kReadsPerReader; ++i) {
        const ReadResult res = cell->read(out);
        if (!res.ok()) {
          continue;
        }
        ++good;
        ok.fetch_add(1, std::memory_order_relaxed);
        if (!out.intact() || out.counter != res.sequence ||
            res.publish_time_ns != static_cast<std::int64_t>(res.sequence)) {
          corrupt.fetch_add(1, std::memory_order_relaxed);
        }
        if (res.sequence < last) {
          backwards.fetch_add(1, std::memory_order_relaxed);
        }
        last = res.sequence;
      }
    });
  }
  for (auto& t : readers) {
    t.join();
  }
  stop = true;
  writer.join();
  EXPECT_EQ(corrupt.load(), 0U);
  EXPECT_EQ(backwards.load(), 0U);
  EXPECT_EQ(ok.load(), 3 * kReadsPerReader) << "every reader checked its quota of snapshots";
}

}  // namespace
}  // namespace hapticctrl::shm
