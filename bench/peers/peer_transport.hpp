#pragma once
/// @file peer_transport.hpp
/// The transports the peer benchmark sets side by side (H8): hapticctrl's seqlock region, iceoryx
/// publish/subscribe, LCM (udpm, ttl=0), UDP loopback, and DDS (H7: hapticctrl-dds's middleware),
/// each behind the same two small interfaces so that one measurement serves them all. A message is
/// a VP payload as the core publishes it, with the message number in `cycle` and its publish time
/// (CLOCK_MONOTONIC) in `echo_client_time_ns`.
///
/// A transport is set up in the parent before the processes fork (setup()), then each process
/// makes its own end after the fork (make_writer(), make_reader()). Not for a real-time cycle:
/// benchmark code.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::bench {

using Message = shm::VpPayload;

/// The writer's end: publishes the newest value (and wakes readers where the transport does).
class PeerWriter {
 public:
  virtual ~PeerWriter() = default;
  /// False when the transport refused or failed the publish (counted, not retried).
  virtual bool publish(const Message& message) = 0;
};

/// The reader's end.
class PeerReader {
 public:
  virtual ~PeerReader() = default;
  /// Blocks until something new may be readable, or `timeout`. False on timeout.
  virtual bool wait(std::chrono::milliseconds timeout) = 0;
  /// The newest message if one arrived since the last read (latest value: older ones are
  /// skipped), without blocking.
  virtual bool read(Message& out) = 0;
};

/// How a reader is driven.
enum class ReadMode : std::uint8_t {
  kPoll,  ///< read() in a loop, never blocking
  kWake,  ///< wait() then read()
};

/// One transport and what it guarantees.
class PeerTransport {
 public:
  virtual ~PeerTransport() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  /// The read modes it offers (a socket has no "latest value" to poll without a syscall).
  [[nodiscard]] virtual std::vector<ReadMode> modes() const = 0;
  /// Parent, before each run's fork. Throws std::runtime_error with what is missing.
  virtual void setup(ReadMode mode) = 0;
  /// After the fork, in the writer's and the reader's process.
  virtual std::unique_ptr<PeerWriter> make_writer(ReadMode mode) = 0;
  virtual std::unique_ptr<PeerReader> make_reader(ReadMode mode) = 0;
  /// Parent, after each run.
  virtual void teardown() {}
};

std::unique_ptr<PeerTransport> make_seqlock_transport();
std::unique_ptr<PeerTransport> make_iceoryx_transport();
std::unique_ptr<PeerTransport> make_lcm_transport();
std::unique_ptr<PeerTransport> make_udp_transport();
std::unique_ptr<PeerTransport> make_dds_transport();

[[nodiscard]] inline const char* mode_name(ReadMode mode) {
  return mode == ReadMode::kPoll ? "poll" : "wake";
}

}  // namespace hapticctrl::bench
