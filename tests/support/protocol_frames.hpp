#pragma once
// Test support of the protocol's tests: one valid frame of every type (round trips, mutation,
// sizes), a control frame with an object state and a timed one for the bridge's tests.
#include <cstdint>
#include <cstring>
#include <vector>

#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::protocol::test {

inline constexpr std::uint64_t kToken = 0x0102030405060708ULL;

inline hcp_frame object_frame() {
  hcp_frame f = make_frame(HCP_CONTROL_OBJECT, kToken, 43, 2'000'000'000);
  const float pose[7] = {0.1F, 0.2F, 0.3F, 0, 0, 0, 1};  // NOLINT(*-avoid-c-arrays)
  const float twist[6] = {0.5F, 0, 0, 0, 0, 0.25F};      // NOLINT(*-avoid-c-arrays)
  std::memcpy(f.body.hcp_body_u.object.pose, pose, sizeof pose);
  std::memcpy(f.body.hcp_body_u.object.twist, twist, sizeof twist);
  return f;
}

/// A CONTROL_OBJECT_TIMED frame at the origin, unturned, echoing answer `answer_cycle` that the
/// client held `hold_ns`, with the client's energy in (µJ); the caller places the object.
inline hcp_frame timed_object_frame(std::uint64_t token, std::uint32_t sequence, std::int64_t now,
                                    std::uint64_t answer_cycle, std::int64_t hold_ns,
                                    std::uint32_t energy_uj) {
  hcp_frame f = make_frame(HCP_CONTROL_OBJECT_TIMED, token, sequence, now);
  hcp_control_object_timed& t = f.body.hcp_body_u.timed;
  const auto r = pack_rotation({0, 0, 0, 1});
  t.rotation[0] = r[0];
  t.rotation[1] = r[1];
  t.answer_echo = pack_answer_echo(answer_cycle, hold_ns, true);
  t.energy_in = energy_uj;
  return f;
}

/// One valid frame of every type, for round trips and mutation.
inline std::vector<hcp_frame> one_of_each() {
  std::vector<hcp_frame> frames;
  hcp_frame hello = make_frame(HCP_HELLO, 0, 1, 10);
  hello.body.hcp_body_u.hello.min_version = kVersion;
  hello.body.hcp_body_u.hello.features = kAllFeatures;
  hello.body.hcp_body_u.hello.watchdog_ms = 250;
  set_text(hello.body.hcp_body_u.hello.client_name, "physics-engine");
  frames.push_back(hello);
  hcp_frame welcome = make_frame(HCP_WELCOME, kToken, 1, 11);
  welcome.body.hcp_body_u.welcome = {HCP_FEATURE_JOINT_STATE, 100, 1'000'000, 12345};
  frames.push_back(welcome);
  hcp_frame refuse = make_frame(HCP_REFUSE, 0, 2, 12);
  refuse.body.hcp_body_u.refuse.code = HCP_REFUSE_BUSY;
  refuse.body.hcp_body_u.refuse.peer_version = kVersion;
  refuse.body.hcp_body_u.refuse.retry_after_ms = 40;
  set_text(refuse.body.hcp_body_u.refuse.reason, "busy");
  frames.push_back(refuse);
  frames.push_back(object_frame());
  hcp_frame wrench = make_frame(HCP_CONTROL_WRENCH, kToken, 3, 13);
  wrench.body.hcp_body_u.wrench.wrench[2] = -4.5F;
  frames.push_back(wrench);
  frames.push_back(make_frame(HCP_KEEPALIVE, kToken, 4, 14));
  hcp_frame answer = make_frame(HCP_ANSWER, kToken, 5, 15);
  hcp_answer& a = answer.body.hcp_body_u.answer;
  a.cycle = 99;
  a.echo_sequence = 3;
  a.echo_time_ns = 13;
  a.state_word = 0x11;
  a.core_state = 1;
  a.control_received = 7;
  a.coupling_wrench[0] = 1.5;
  a.handle_pose[6] = 1.0;
  a.handle_pose[0] = 0.25;
  a.joint_position[5] = -0.5;
  frames.push_back(answer);
  hcp_frame timed = timed_object_frame(kToken, 6, 15, 1234, 300'000, 0xFFFFFFF0U);
  hcp_control_object_timed& t = timed.body.hcp_body_u.timed;
  t.position[0] = 0.5F;
  const auto packed = pack_rotation({0.1, 0.2, 0.3, 0.9});
  t.rotation[0] = packed[0];
  t.rotation[1] = packed[1];
  t.twist[3] = 0.25F;
  frames.push_back(timed);
  hcp_frame answer_timed = make_frame(HCP_ANSWER_TIMED, kToken, 7, 15);
  answer_timed.body.hcp_body_u.answer_timed.answer = a;
  hcp_coupling_report& c = answer_timed.body.hcp_body_u.answer_timed.coupling;
  c.energy_in = 1.25;
  c.loop_delay_s = 0.011;
  c.link_loss = 0.1;
  c.gains[0] = 868.0;
  frames.push_back(answer_timed);
  hcp_frame coupled = make_frame(HCP_ANSWER_COUPLED, kToken, 8, 15);
  coupled.body.hcp_body_u.answer_coupled.answer = a;
  coupled.body.hcp_body_u.answer_coupled.coupling = c;
  hcp_local_coupling& l = coupled.body.hcp_body_u.answer_coupled.local;
  l.contact_normal[0] = -1.0;
  l.normal_gains[0] = 930.0;
  l.limits[0] = 35.0;
  l.limits[1] = 3.0;
  l.max_contact_stiffness = 2000.0;
  l.contacts = 1;
  frames.push_back(coupled);
  hcp_frame wrench_timed = make_frame(HCP_CONTROL_WRENCH_TIMED, kToken, 9, 15);
  wrench_timed.body.hcp_body_u.wrench_timed.wrench[0] = -8.0F;
  wrench_timed.body.hcp_body_u.wrench_timed.answer_echo = pack_answer_echo(1234, 300'000, true);
  wrench_timed.body.hcp_body_u.wrench_timed.energy_in = 77U;
  frames.push_back(wrench_timed);
  hcp_frame contact = make_frame(HCP_CONTROL_CONTACT, kToken, 10, 15);
  contact.body.hcp_body_u.contact.slots = pack_contact_slots(1, 2);
  hcp_contact& k = contact.body.hcp_body_u.contact.contact;
  k.point[0] = 0.6F;
  k.normal[0] = -1.0F;
  k.distance = -0.001F;
  k.stiffness = 2000.0F;
  k.damping = 5.0F;
  k.friction[0] = 0.5F;
  k.friction[1] = 0.4F;
  frames.push_back(contact);
  hcp_frame joint_target = make_frame(HCP_CONTROL_JOINT_TARGET, kToken, 11, 15);
  joint_target.body.hcp_body_u.joint_target.position[1] = -0.6F;
  joint_target.body.hcp_body_u.joint_target.speed[5] = 0.25F;
  frames.push_back(joint_target);
  hcp_frame joint_torque = make_frame(HCP_CONTROL_JOINT_TORQUE, kToken, 12, 15);
  joint_torque.body.hcp_body_u.joint_torque.torque[0] = -1.5F;
  frames.push_back(joint_torque);
  for (int id = HCP_P_TIME_STEP; id <= HCP_P_EMERGENCY_RESET; ++id) {
    hcp_frame p = make_frame(HCP_PARAM, kToken, static_cast<std::uint32_t>(10 + id), 16);
    hcp_param& q = p.body.hcp_body_u.param;
    q.id = static_cast<hcp_param_id>(id);
    q.hcp_param_u.base_frame[6] = 1.0;  // a unit quaternion for the frame parameters
    q.hcp_param_u.time_step = 0.002;    // overlaps base_frame[0]; also factor and speed
    if (q.id == HCP_P_WATCHDOG) {
      q.hcp_param_u.watchdog_ms = 200;
    } else if (q.id == HCP_P_OBJECT) {
      q.hcp_param_u.object = {1, 0.5, {0.01, 0.01, 0.01}};
    } else if (q.id == HCP_P_INDEXING_MODE || q.id == HCP_P_COMMAND_TYPE) {
      q.hcp_param_u.command_type = 2;
    } else if (q.id == HCP_P_GAINS) {
      q.hcp_param_u.gains[1] = 3.0;
    }
    frames.push_back(p);
  }
  hcp_frame ack = make_frame(HCP_ACK, kToken, 6, 17);
  ack.body.hcp_body_u.ack.acked_sequence = 12;
  ack.body.hcp_body_u.ack.status = HCP_ACK_REJECTED;
  set_text(ack.body.hcp_body_u.ack.reason, "force factor: between 0.001 and 1000");
  frames.push_back(ack);
  frames.push_back(make_frame(HCP_BYE, kToken, 20, 18));
  return frames;
}

}  // namespace hapticctrl::protocol::test
