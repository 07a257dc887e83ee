#pragma once
// Test support for the client's protocol state machine (client/src/client_session.hpp): the
// controller's side of a handshake and its answers, and a session welcomed at t = 0.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>

#include "client_session.hpp"
#include "hapticctrl/protocol/codec.hpp"

namespace hapticctrl::client::test {

using namespace std::chrono_literals;

/// The moment `t` after the clock's origin.
inline TimePoint at(Duration t) {
  return TimePoint{t};
}
inline constexpr std::uint64_t kToken = 0x1234'5678'9abc'def0ULL;

inline ConnectOptions options() {
  ConnectOptions o;
  o.retransmit_after = 20ms;
  o.connect_timeout = 500ms;
  o.answer_timeout = 300ms;
  return o;
}

inline hcp_frame welcome(std::uint32_t version = protocol::kVersion) {
  hcp_frame w = protocol::make_frame(HCP_WELCOME, kToken, 1, 0);
  w.header.protocol = version;
  w.body.hcp_body_u.welcome.features = protocol::kAllFeatures;
  w.body.hcp_body_u.welcome.watchdog_ms = 400;
  w.body.hcp_body_u.welcome.period_ns = to_ns(1ms);
  return w;
}

inline hcp_frame answer(std::uint32_t sequence, std::uint64_t cycle) {
  hcp_frame f = protocol::make_frame(HCP_ANSWER_TIMED, kToken, sequence, 0);
  hcp_answer& a = f.body.hcp_body_u.answer_timed.answer;
  a.cycle = cycle;
  a.core_state = 1;
  a.handle_pose[6] = 1.0;
  a.coupling_wrench[0] = 2.5;
  return f;
}

/// A session welcomed at t = 0.
inline ClientSession open_session() {
  ClientSession s(options(), "127.0.0.1:5125");
  EXPECT_TRUE(s.hello_due(at(0ms)).has_value());
  EXPECT_TRUE(s.on_handshake_frame(welcome(), at(0ms)).welcomed);
  s.on_sent(at(0ms));
  return s;
}

}  // namespace hapticctrl::client::test
