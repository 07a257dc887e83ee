#pragma once
/// @file peer_runner.hpp
/// One measured run of a transport: a writer process and a reader process (forked, placed on
/// their CPUs at one priority, the same for every transport), the writer publishing numbered,
/// timestamped messages at a fixed rate, the reader taking them in its mode. Collected: every
/// message's publish -> observed latency, the cost of each publish and of each read that got a
/// message, the CPU time of both processes, and, for a stall run, the publish cost while the
/// reader runs, is stopped (SIGSTOP) and is killed. Benchmark code, not for a cycle.

#include <cstdint>
#include <string>
#include <vector>

#include "peers/peer_transport.hpp"

namespace hapticctrl::bench {

struct Placement {
  int writer_cpu = -1;  ///< -1: any
  int reader_cpu = -1;
  /// SCHED_FIFO priority of the writer and of a woken reader (0: SCHED_OTHER); a polling reader
  /// spins at SCHED_OTHER (peer_runner.cpp says why).
  int priority = 0;
};

struct RunConfig {
  ReadMode mode = ReadMode::kWake;
  double rate_hz = 1000.0;
  std::uint32_t messages = 1000;
  /// The reader is stopped for the middle 40 % of the messages and killed for the last 20 %.
  bool stall_reader = false;
};

/// Phases of a stall run.
enum class Phase : std::uint8_t { kRunning = 0, kStopped = 1, kResumed = 2, kKilled = 3 };
inline constexpr std::size_t kPhases = 4;

struct RunResult {
  std::vector<std::int64_t> latency_ns;  ///< one per message the reader saw
  std::vector<std::int64_t> read_ns;     ///< one per read that got a message
  std::vector<std::int64_t> publish_ns;  ///< one per publish
  std::vector<Phase> publish_phase;      ///< the phase of each publish (stall runs)
  std::uint64_t failed_publishes = 0;
  double writer_cpu_s = 0.0;  ///< user + system
  double reader_cpu_s = 0.0;
  std::string error;  ///< why the run could not be made (empty: it was)
};

/// Runs `config` on `transport` (set up, forked, torn down). Never throws: a transport that
/// cannot run says why in RunResult::error.
RunResult run_peers(PeerTransport& transport, const RunConfig& config, const Placement& placement);

/// The cost of one clock read (median of a pair), subtracted from every cost above.
std::int64_t clock_read_ns();

}  // namespace hapticctrl::bench
