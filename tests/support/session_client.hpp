#pragma once
// A scripted protocol client and the fixture that drives the UDP bridge's Session with it
// (tests/bridges/session*_test.cpp): frames built, fed as datagrams, replies decoded.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "hapticctrl/protocol/values.hpp"
#include "hapticctrl/udp_bridge/session.hpp"
#include "support/in_memory_controller.hpp"
#include "support/protocol_frames.hpp"

namespace hapticctrl::test {

using protocol::Endpoint;
using protocol::FrameBuffer;
using udp_bridge::Session;

using namespace std::chrono_literals;

using Controller = InMemoryController;

/// A scripted client: builds frames, feeds them to the session, decodes the reply.
struct Client {
  Session* session = nullptr;
  Endpoint from = Endpoint::resolve("127.0.0.1", 40000);
  std::uint64_t token = 0;
  std::uint32_t control_seq = 0;
  std::uint32_t param_seq = 0;
  TimePoint now{1s};
  hcp_frame reply{};
  bool replied = false;
  std::uint32_t asked_watchdog_ms = 0;  ///< in the HELLO (0: the bridge's default)

  std::vector<std::uint8_t> bytes(hcp_frame f) const {
    FrameBuffer b{};
    const std::size_t n = protocol::encode(f, b);
    return {b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n)};
  }
  void feed(const std::vector<std::uint8_t>& data) {
    FrameBuffer out{};
    const std::size_t n = session->on_datagram(data, from, now, out);
    replied = n != 0;
    if (replied) {
      ASSERT_EQ(protocol::decode({out.data(), n}, reply), protocol::DecodeStatus::kOk);
    }
  }
  void hello(std::uint32_t version = protocol::kVersion,
             std::uint32_t features = protocol::kAllFeatures, std::uint32_t min_version = 0) {
    hcp_frame f = protocol::make_frame(HCP_HELLO, 0, 1, to_ns(now));
    f.header.protocol = version;
    f.body.hcp_body_u.hello.min_version = min_version != 0 ? min_version : version;
    f.body.hcp_body_u.hello.features = features;
    f.body.hcp_body_u.hello.watchdog_ms = asked_watchdog_ms;
    feed(bytes(f));
    if (replied && reply.body.type == HCP_WELCOME) {
      token = reply.header.token;
    }
  }
  hcp_frame object(float x) {
    hcp_frame f = protocol::make_frame(HCP_CONTROL_OBJECT, token, ++control_seq, to_ns(now));
    f.body.hcp_body_u.object.pose[0] = x;
    f.body.hcp_body_u.object.pose[6] = 1.0F;
    return f;
  }
  void send_object(float x) { feed(bytes(object(x))); }
  /// A CONTROL_OBJECT_TIMED frame echoing answer `answer_cycle`, held `hold` by the client.
  hcp_frame timed_object(std::uint64_t answer_cycle, Duration hold, std::uint32_t energy_uj) {
    hcp_frame f = protocol::test::timed_object_frame(token, ++control_seq, to_ns(now), answer_cycle,
                                                     to_ns(hold), energy_uj);
    f.body.hcp_body_u.timed.position[0] = 0.3F;
    return f;
  }
  hcp_frame param(hcp_param_id id) {
    hcp_frame f = protocol::make_frame(HCP_PARAM, token, ++param_seq, to_ns(now));
    f.body.hcp_body_u.param.id = id;
    return f;
  }
};

struct SessionTest : ::testing::Test {
  Controller controller;
  std::uint64_t next_token = 0x1111;
  Session session{{100}, [this] { return next_token++; }};
  Client client{&session};

  void SetUp() override { session.set_controller(&controller.ports, TimePoint{}); }
  std::uint64_t dropped(shm::LinkDrop why) { return session.counters().dropped_for(why); }
};

}  // namespace hapticctrl::test
