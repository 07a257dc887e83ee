#pragma once
/// @file seqlock.hpp
/// A single-writer, multi-reader seqlock cell that lives in shared memory.
///
/// Memory-model argument (why this is correct without a single plain memcpy racing the writer):
///  - The payload is stored as an array of `std::atomic<std::uint64_t>` words. Every access to
///    it, by the writer and by readers, is atomic, so there is no data race by definition and
///    ThreadSanitizer has nothing to report.
///  - Writer: `seq = s+1` (relaxed), then every payload word with a *release* store, then
///    `seq = s+2` (release). Reader: `s1 = seq` (acquire), every word with an *acquire* load,
///    then `s2 = seq` (relaxed); accept only if `s1 == s2` and `s1` is even.
///  - If the reader loads any word written by a later write, its acquire load synchronises with
///    that word's release store, which is sequenced after `seq = odd`; so the reader's final load
///    of `seq` cannot see the old even value and the snapshot is rejected. If `s1` is the
///    completed even value, the acquire on `s1` makes every word of that write visible.
///  - On x86-64, acquire loads and release stores compile to plain moves, so this costs the same
///    as the fence-based variant, and it avoids `atomic_thread_fence`, which ThreadSanitizer does
///    not model.
///
/// The 32-bit `seq` word is also the futex word readers block on (see wait_for_publish()); it
/// wraps after 2^31 publishes, and nothing depends on its value but its parity and its change.
/// The 64-bit sample sequence returned to readers is stored inside the protected area, so it
/// never wraps in practice (2^64 publishes); it also tells a cell never written (0).

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/base/time.hpp"
#include "hapticctrl/shm/futex.hpp"

namespace hapticctrl::shm {

/// Spin-wait hint (x86 PAUSE); a no-op elsewhere.
HAPTICCTRL_RT inline void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

/// Outcome of a seqlock read.
enum class ReadStatus : std::uint8_t {
  kOk,            ///< a consistent snapshot was copied out
  kTorn,          ///< every attempt overlapped a write (or a writer died mid-write): gave up
  kNeverWritten,  ///< the cell has never been published
};

/// What a reader learns besides the payload.
struct ReadResult {
  ReadStatus status = ReadStatus::kNeverWritten;
  /// 1 for the first publish, +1 per publish; a reader compares it with the last one it saw to
  /// tell fresh (+1), stale (same) and lost (> +1) samples. 0 unless status is kOk.
  std::uint64_t sequence = 0;
  /// The writer's timestamp for this sample (CLOCK_MONOTONIC ns, as passed to publish()).
  std::int64_t publish_time_ns = 0;

  [[nodiscard]] HAPTICCTRL_RT bool ok() const noexcept { return status == ReadStatus::kOk; }
};

/// Default number of read attempts before a read reports kTorn. A write of a VP-sized payload
/// takes well under a microsecond, so 64 attempts only fail when the writer is stuck or dead.
inline constexpr unsigned kDefaultReadAttempts = 64;

/// Outcome of wait_for_publish().
enum class WaitStatus : std::uint8_t { kPublished, kTimedOut };

/// A seqlock cell holding one `T`. It is placed in shared memory by the segment creator (placement
/// new) and used in place by every process; it holds no pointers.
template <typename T>
class alignas(64) SeqlockCell {
  static_assert(std::is_trivially_copyable_v<T>, "seqlock payloads must be trivially copyable");
  static_assert(sizeof(T) % sizeof(std::uint64_t) == 0,
                "pad seqlock payloads to a multiple of 8 bytes (explicit layout)");
  static_assert(alignof(T) <= alignof(std::uint64_t), "payload alignment above 8 is unsupported");

 public:
  using Payload = T;
  static constexpr std::size_t kWords = sizeof(T) / sizeof(std::uint64_t);

  SeqlockCell() noexcept {
    for (auto& word : words_) {
      word.store(0, std::memory_order_relaxed);
    }
  }

  /// Publishes `value` stamped with `publish_time_ns` and wakes blocked readers.
  /// Only the one writer of this cell may call it (enforced by the region's writer claim).
  /// Real-time contract: safe in the cycle; wait-free; one futex-wake syscall.
  HAPTICCTRL_RT void publish(const T& value, std::int64_t publish_time_ns) noexcept {
    publish_quietly(value, publish_time_ns);
    futex_wake_all(seq_);
  }

  /// publish() without the wake-up syscall, for cells nobody blocks on.
  /// Real-time contract: safe in the cycle; wait-free; no syscall.
  HAPTICCTRL_RT void publish_quietly(const T& value, std::int64_t publish_time_ns) noexcept {
    const std::uint32_t start = seq_.load(std::memory_order_relaxed);
    seq_.store(start + 1, std::memory_order_relaxed);
    count_.store(count_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
    stamp_.store(publish_time_ns, std::memory_order_release);
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t i = 0; i < kWords; ++i) {
      std::uint64_t word = 0;
      std::memcpy(&word, bytes + i * sizeof(word), sizeof(word));
      words_[i].store(word, std::memory_order_release);
    }
    seq_.store(start + 2, std::memory_order_release);
  }

  /// Copies a consistent snapshot into `out`, trying at most `max_attempts` times.
  /// `out` is only modified when the result is kOk.
  /// Real-time contract: safe in the cycle; bounded; never blocks the writer or waits for it.
  HAPTICCTRL_RT ReadResult read(T& out,
                                unsigned max_attempts = kDefaultReadAttempts) const noexcept {
    std::array<std::uint64_t, kWords> scratch;  // NOLINT(cppcoreguidelines-pro-type-member-init)
    for (unsigned attempt = 0; attempt < max_attempts; ++attempt) {
      const std::uint32_t before = seq_.load(std::memory_order_acquire);
      if ((before & 1U) != 0) {
        cpu_relax();  // a write is in progress: give it a moment instead of burning attempts
        continue;
      }
      // "Never written" from the publish count, which a write raises before its payload: the
      // 32-bit word is 0 again after 2^31 publishes (24.9 days at 1 kHz, 2.5 days at 10 kHz),
      // and a read then said kNeverWritten (J4).
      const std::uint64_t sequence = count_.load(std::memory_order_acquire);
      if (sequence == 0) {
        return ReadResult{ReadStatus::kNeverWritten, 0, 0};
      }
      const std::int64_t stamp = stamp_.load(std::memory_order_acquire);
      for (std::size_t i = 0; i < kWords; ++i) {
        scratch[i] = words_[i].load(std::memory_order_acquire);
      }
      if (seq_.load(std::memory_order_relaxed) == before) {
        std::memcpy(static_cast<void*>(&out), scratch.data(), sizeof(T));
        return ReadResult{ReadStatus::kOk, sequence, stamp};
      }
    }
    return ReadResult{ReadStatus::kTorn, 0, 0};
  }

  /// The current value of the sequence word; pass it to wait_for_publish() to wait for the
  /// next publish after this point. Real-time contract: safe anywhere.
  [[nodiscard]] std::uint32_t sequence_word() const noexcept {
    return seq_.load(std::memory_order_acquire);
  }

  /// Number of completed publishes (what ReadResult::sequence reports for the latest sample).
  [[nodiscard]] std::uint64_t publish_count() const noexcept {
    return count_.load(std::memory_order_acquire);
  }

  /// Blocks until a publish completes after `seen` (a value from sequence_word()), or `timeout`
  /// elapses. Returns at once if one already did. A writer that died mid-write leaves the word
  /// odd: the wait then simply times out, so a dead writer never hangs a reader.
  /// Real-time contract: blocking; never call from the cycle.
  WaitStatus wait_for_publish(std::uint32_t seen, std::chrono::nanoseconds timeout) const noexcept {
    const auto deadline = hapticctrl::MonotonicClock::now() + timeout;
    for (;;) {
      const std::uint32_t current = seq_.load(std::memory_order_acquire);
      if (current != seen && (current & 1U) == 0) {
        return WaitStatus::kPublished;
      }
      const auto left = deadline - hapticctrl::MonotonicClock::now();
      if (left <= std::chrono::nanoseconds::zero()) {
        return WaitStatus::kTimedOut;
      }
      futex_wait(seq_, current, std::chrono::duration_cast<std::chrono::nanoseconds>(left));
    }
  }

  /// Test and tooling hook: the raw sequence word (odd while a write is in progress).
  [[nodiscard]] std::atomic<std::uint32_t>& raw_sequence_word() noexcept { return seq_; }

 private:
  std::atomic<std::uint32_t> seq_{0};
  std::uint32_t reserved_ = 0;
  std::atomic<std::uint64_t> count_{0};
  std::atomic<std::int64_t> stamp_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_;
};

}  // namespace hapticctrl::shm
