#pragma once
/// Cyclone DDS kept on this host for tests: the loopback interface, unicast discovery to
/// 127.0.0.1 (loopback has no multicast), and a domain of each test process's own, so test
/// binaries running side by side do not discover each other. Every program a test starts
/// inherits $CYCLONEDDS_URI.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>

namespace hapticctrl::test {

inline constexpr const char* kLoopbackDdsConfig =
    "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General>"
    "<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>20"
    "</MaxAutoParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>";

/// Sets $CYCLONEDDS_URI to the loopback configuration (before any participant is created) and
/// returns this process's domain, 1..100: DDS puts domain d on ports 7400 + 250 d and a few
/// above, so they all stay below Linux's ephemeral ports (32768 on).
inline std::uint32_t use_loopback_dds() {
  setenv("CYCLONEDDS_URI", kLoopbackDdsConfig, 1);  // NOLINT(concurrency-mt-unsafe): test setup
  return 1 + static_cast<std::uint32_t>(getpid()) % 100;
}

}  // namespace hapticctrl::test
