// Codec: golden bytes (computed independently with Python's struct and zlib), round trips for
// every frame type, the 90-byte control limit, and every rejection path.
#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "hapticctrl/protocol/values.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace hapticctrl::protocol {
namespace {

constexpr std::uint64_t kToken = 0x0102030405060708ULL;

std::string hex(std::span<const std::uint8_t> bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (const std::uint8_t b : bytes) {
    out += digits[b >> 4U];
    out += digits[b & 15U];
  }
  return out;
}

std::vector<std::uint8_t> encoded(hcp_frame frame) {
  FrameBuffer buffer{};
  const std::size_t n = encode(frame, buffer);
  return {buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n)};
}

hcp_frame object_frame() {
  hcp_frame f = make_frame(HCP_CONTROL_OBJECT, kToken, 43, 2'000'000'000);
  const float pose[7] = {0.1F, 0.2F, 0.3F, 0, 0, 0, 1};  // NOLINT(*-avoid-c-arrays)
  const float twist[6] = {0.5F, 0, 0, 0, 0, 0.25F};      // NOLINT(*-avoid-c-arrays)
  std::memcpy(f.body.hcp_body_u.object.pose, pose, sizeof pose);
  std::memcpy(f.body.hcp_body_u.object.twist, twist, sizeof twist);
  return f;
}

TEST(Codec, KeepaliveGoldenBytes) {
  const auto bytes = encoded(make_frame(HCP_KEEPALIVE, kToken, 42, 1'000'000'000));
  EXPECT_EQ(hex(bytes), "484354500001000401020304050607080000002a000000003b9aca0000000006dad92d41");
}

TEST(Codec, ControlObjectGoldenBytesAndSize) {
  const auto bytes = encoded(object_frame());
  EXPECT_EQ(bytes.size(), 88U);
  EXPECT_LE(bytes.size(), kControlMaxBytes);
  EXPECT_EQ(hex(bytes),
            "484354500001000401020304050607080000002b0000000077359400000000043dcccccd3e4ccccd3e"
            "99999a0000000000000000000000003f8000003f000000000000000000000000000000000000003e80"
            "00004d278a33");
}

TEST(Codec, ControlWrenchGoldenBytes) {
  hcp_frame f = make_frame(HCP_CONTROL_WRENCH, kToken, 44, 3);
  const float w[6] = {1, -2, 3, 0, 0, 0.5F};  // NOLINT(*-avoid-c-arrays)
  std::memcpy(f.body.hcp_body_u.wrench.wrench, w, sizeof w);
  const auto bytes = encoded(f);
  EXPECT_EQ(bytes.size(), 60U);
  EXPECT_EQ(hex(bytes),
            "484354500001000401020304050607080000002c0000000000000003000000053f800000c00000004040"
            "000000000000000000003f000000f2804988");
}

TEST(Codec, ParamGoldenBytes) {
  hcp_frame f = make_frame(HCP_PARAM, kToken, 7, 4);
  f.body.hcp_body_u.param.id = HCP_P_TIME_STEP;
  f.body.hcp_body_u.param.hcp_param_u.time_step = 0.001;
  EXPECT_EQ(hex(encoded(f)),
            "4843545000010004010203040506070800000007000000000000000400000008000000013f50624dd2f1a9"
            "fcb02f281d");
}

TEST(Codec, EveryParameterA12ClientSendsFitsInNinetyBytes) {
  // H2: PARAM BASE_FRAME and OBSERVATION_FRAME in double precision made 96 bytes; 1.2 clients
  // send them as _SP (68). The double forms stay decodable for 1.1 clients.
  for (int id = HCP_P_TIME_STEP; id <= HCP_P_OBSERVATION_FRAME_SP; ++id) {
    hcp_frame f = make_frame(HCP_PARAM, kToken, 7, 4);
    f.body.hcp_body_u.param.id = static_cast<hcp_param_id>(id);
    const std::size_t n = encoded(f).size();
    if (id == HCP_P_BASE_FRAME || id == HCP_P_OBSERVATION_FRAME) {
      EXPECT_EQ(n, 96U) << id;
    } else {
      EXPECT_LE(n, kControlMaxBytes) << "parameter " << id;
    }
  }
  hcp_frame f = make_frame(HCP_PARAM, kToken, 7, 4);
  f.body.hcp_body_u.param.id = HCP_P_BASE_FRAME_SP;
  EXPECT_EQ(encoded(f).size(), 68U);
}

TEST(Codec, EveryControlFrameFitsTheSeedLimit) {
  for (const hcp_frame_type type : {HCP_CONTROL_OBJECT, HCP_CONTROL_WRENCH, HCP_KEEPALIVE}) {
    hcp_frame f = type == HCP_CONTROL_OBJECT ? object_frame() : make_frame(type, kToken, 1, 1);
    EXPECT_LE(encoded(f).size(), kControlMaxBytes) << type;
  }
}

/// One valid frame of every type, for round trips and mutation.
std::vector<hcp_frame> one_of_each() {
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
  hcp_frame timed = make_frame(HCP_CONTROL_OBJECT_TIMED, kToken, 6, 15);
  hcp_control_object_timed& t = timed.body.hcp_body_u.timed;
  t.position[0] = 0.5F;
  const auto packed = pack_rotation({0.1, 0.2, 0.3, 0.9});
  t.rotation[0] = packed[0];
  t.rotation[1] = packed[1];
  t.twist[3] = 0.25F;
  t.answer_echo = pack_answer_echo(1234, 300'000, true);
  t.energy_in = 0xFFFFFFF0U;
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

TEST(Codec, EveryFrameTypeRoundTrips) {
  for (const hcp_frame& original : one_of_each()) {
    const auto bytes = encoded(original);
    ASSERT_GE(bytes.size(), kMinFrameBytes) << original.body.type;
    hcp_frame back;
    ASSERT_EQ(decode(bytes, back), DecodeStatus::kOk) << original.body.type;
    // Re-encoding the decoded frame gives the same bytes: nothing was lost or invented.
    EXPECT_EQ(encoded(back), bytes) << original.body.type;
    EXPECT_EQ(back.header.token, original.header.token);
    EXPECT_EQ(back.header.sequence, original.header.sequence);
  }
}

TEST(Codec, FrameSizesAreAsDocumented) {  // docs/protocol.md, "Frames"
  std::map<hcp_frame_type, std::size_t> largest;
  for (const hcp_frame& f : one_of_each()) {
    largest[f.body.type] = std::max(largest[f.body.type], encoded(f).size());
  }
  EXPECT_EQ(largest[HCP_HELLO], 80U);
  EXPECT_EQ(largest[HCP_WELCOME], 60U);
  EXPECT_EQ(largest[HCP_REFUSE], 144U);
  EXPECT_EQ(largest[HCP_CONTROL_OBJECT], 88U);
  EXPECT_EQ(largest[HCP_CONTROL_OBJECT_TIMED], 88U);
  EXPECT_LE(largest[HCP_CONTROL_OBJECT_TIMED], kControlMaxBytes);
  EXPECT_EQ(largest[HCP_ANSWER_TIMED], 404U);
  EXPECT_EQ(largest[HCP_ANSWER_COUPLED], 476U);
  EXPECT_LE(largest[HCP_ANSWER_COUPLED], kMaxFrameBytes);
  EXPECT_EQ(largest[HCP_CONTROL_WRENCH_TIMED], 68U);
  EXPECT_EQ(largest[HCP_CONTROL_CONTACT], 88U);
  EXPECT_LE(largest[HCP_CONTROL_CONTACT], kControlMaxBytes);
  EXPECT_EQ(largest[HCP_CONTROL_WRENCH], 60U);
  EXPECT_EQ(largest[HCP_CONTROL_JOINT_TARGET], 84U);
  EXPECT_LE(largest[HCP_CONTROL_JOINT_TARGET], kControlMaxBytes);
  EXPECT_EQ(largest[HCP_CONTROL_JOINT_TORQUE], 60U);
  EXPECT_EQ(largest[HCP_KEEPALIVE], 36U);
  EXPECT_EQ(largest[HCP_ANSWER], 324U);
  EXPECT_EQ(largest[HCP_PARAM], 96U);
  EXPECT_EQ(largest[HCP_ACK], 140U);
  EXPECT_EQ(largest[HCP_BYE], 36U);
}

TEST(Codec, TextFieldsAreTerminatedAndTruncated) {
  hcp_frame f = make_frame(HCP_REFUSE, 0, 1, 1);
  set_text(f.body.hcp_body_u.refuse.reason, std::string(500, 'x'));
  EXPECT_EQ(text_of(f.body.hcp_body_u.refuse.reason).size(), HCP_TEXT_BYTES - 1U);
  set_text(f.body.hcp_body_u.refuse.reason, "short");
  EXPECT_EQ(text_of(f.body.hcp_body_u.refuse.reason), "short");
}

TEST(Codec, RejectsBadSizes) {
  const auto bytes = encoded(object_frame());
  hcp_frame out;
  EXPECT_EQ(decode({bytes.data(), 0}, out), DecodeStatus::kBadSize);
  EXPECT_EQ(decode({bytes.data(), 32}, out), DecodeStatus::kBadSize);
  EXPECT_EQ(decode({bytes.data(), bytes.size() - 1}, out), DecodeStatus::kBadSize);
  std::vector<std::uint8_t> big(kMaxFrameBytes + 4, 0);
  EXPECT_EQ(decode(big, out), DecodeStatus::kBadSize);
}

TEST(Codec, TruncationAtAWordBoundaryFailsTheCrcOrDecoding) {
  const auto bytes = encoded(object_frame());
  hcp_frame out;
  for (std::size_t n = kMinFrameBytes; n < bytes.size(); n += 4) {
    EXPECT_NE(decode({bytes.data(), n}, out), DecodeStatus::kOk) << n;
  }
}

TEST(Codec, RejectsBadMagicAndCrc) {
  auto bytes = encoded(object_frame());
  hcp_frame out;
  auto bad_magic = bytes;
  bad_magic[0] ^= 0xFF;
  EXPECT_EQ(decode(bad_magic, out), DecodeStatus::kBadMagic);
  for (std::size_t i = 4; i < bytes.size(); ++i) {  // any single flipped bit after the magic
    auto flipped = bytes;
    flipped[i] ^= 0x10;
    EXPECT_EQ(decode(flipped, out), DecodeStatus::kBadCrc) << i;
  }
}

/// Re-encodes after editing, so that the CRC is right and only the edited field is wrong.
std::vector<std::uint8_t> with_valid_crc(hcp_frame f) {
  return encoded(f);
}

TEST(Codec, RejectsAnotherMajorVersionExceptForHelloAndRefuse) {
  hcp_frame f = object_frame();
  f.header.protocol = make_version(2, 0);
  hcp_frame out;
  EXPECT_EQ(decode(with_valid_crc(f), out), DecodeStatus::kBadVersion);
  hcp_frame hello = one_of_each()[0];
  hello.header.protocol = make_version(7, 3);
  ASSERT_EQ(decode(with_valid_crc(hello), out), DecodeStatus::kOk);
  EXPECT_EQ(out.header.protocol, make_version(7, 3));
  // A newer minor of the same major decodes (minors only add optional features).
  f.header.protocol = make_version(1, 9);
  EXPECT_EQ(decode(with_valid_crc(f), out), DecodeStatus::kOk);
}

/// Recomputes the trailing CRC after a byte-level edit (zlib, as the protocol specifies).
void fix_crc(std::vector<std::uint8_t>& bytes) {
  const std::size_t body = bytes.size() - 4;
  const auto crc = static_cast<std::uint32_t>(::crc32(0UL, bytes.data(), static_cast<uInt>(body)));
  for (std::size_t i = 0; i < 4; ++i) {
    bytes[body + i] = static_cast<std::uint8_t>(crc >> (24U - 8U * i));
  }
}

TEST(Codec, RejectsUnknownFrameTypesParamIdsAndTrailingBytes) {
  hcp_frame out;
  auto bytes = encoded(make_frame(HCP_KEEPALIVE, kToken, 1, 1));
  bytes[31] = 99;  // frame type 99
  fix_crc(bytes);
  EXPECT_EQ(decode(bytes, out), DecodeStatus::kMalformed);

  hcp_frame p = make_frame(HCP_PARAM, kToken, 1, 1);
  p.body.hcp_body_u.param.id = HCP_P_POWER;
  auto param = encoded(p);
  param[35] = 77;  // parameter id 77
  fix_crc(param);
  EXPECT_EQ(decode(param, out), DecodeStatus::kMalformed);

  auto longer = encoded(make_frame(HCP_KEEPALIVE, kToken, 1, 1));
  longer.insert(longer.end() - 4, {0, 0, 0, 0});  // 4 stray bytes before the CRC
  fix_crc(longer);
  EXPECT_EQ(decode(longer, out), DecodeStatus::kMalformed);
}

TEST(Codec, RejectsNonFiniteAndOutOfRangeValues) {
  hcp_frame out;
  for (const float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 1e9F}) {
    hcp_frame f = object_frame();
    f.body.hcp_body_u.object.pose[1] = bad;
    EXPECT_EQ(decode(with_valid_crc(f), out), DecodeStatus::kOutOfRange) << bad;
    hcp_frame w = make_frame(HCP_CONTROL_WRENCH, kToken, 1, 1);
    w.body.hcp_body_u.wrench.wrench[4] = bad;
    EXPECT_EQ(decode(with_valid_crc(w), out), DecodeStatus::kOutOfRange) << bad;
  }
  hcp_frame not_unit = object_frame();
  not_unit.body.hcp_body_u.object.pose[6] = 0.5F;
  EXPECT_EQ(decode(with_valid_crc(not_unit), out), DecodeStatus::kOutOfRange);
}

TEST(Codec, RejectsContactsThatNoSurfaceMakes) {
  hcp_frame out;
  const auto contact = [](const std::function<void(hcp_control_contact&)>& edit) {
    hcp_frame f = make_frame(HCP_CONTROL_CONTACT, kToken, 1, 1);
    hcp_control_contact& c = f.body.hcp_body_u.contact;
    c.slots = pack_contact_slots(0, 1);
    c.contact.normal[2] = 1.0F;
    c.contact.stiffness = 1000.0F;
    c.contact.friction[0] = 0.5F;
    c.contact.friction[1] = 0.5F;
    edit(c);
    return f;
  };
  EXPECT_EQ(decode(with_valid_crc(contact([](hcp_control_contact&) {})), out), DecodeStatus::kOk);
  const std::vector<std::pair<const char*, std::function<void(hcp_control_contact&)>>> bad{
      {"normal not unit", [](hcp_control_contact& c) { c.contact.normal[2] = 0.5F; }},
      {"normal NaN",
       [](hcp_control_contact& c) {
         c.contact.normal[0] = std::numeric_limits<float>::quiet_NaN();
       }},
      {"point far", [](hcp_control_contact& c) { c.contact.point[1] = 1e3F; }},
      {"gap beyond 1 m", [](hcp_control_contact& c) { c.contact.distance = 2.0F; }},
      {"no stiffness", [](hcp_control_contact& c) { c.contact.stiffness = 0.0F; }},
      {"stiffness inf",
       [](hcp_control_contact& c) {
         c.contact.stiffness = std::numeric_limits<float>::infinity();
       }},
      {"negative damping", [](hcp_control_contact& c) { c.contact.damping = -1.0F; }},
      {"dynamic over static", [](hcp_control_contact& c) { c.contact.friction[1] = 0.6F; }},
      {"slot at the count", [](hcp_control_contact& c) { c.slots = pack_contact_slots(1, 1); }},
      {"nine slots", [](hcp_control_contact& c) { c.slots = pack_contact_slots(0, 9); }},
      {"reserved bits", [](hcp_control_contact& c) { c.slots |= 1U << 20U; }},
  };
  for (const auto& [why, edit] : bad) {
    EXPECT_EQ(decode(with_valid_crc(contact(edit)), out), DecodeStatus::kOutOfRange) << why;
  }
  // A count of 0 clears every slot: its contact is not looked at.
  EXPECT_EQ(decode(with_valid_crc(contact([](hcp_control_contact& c) {
                     c.slots = pack_contact_slots(0, 0);
                     c.contact.stiffness = 0.0F;
                   })),
                   out),
            DecodeStatus::kOk);
}

TEST(Codec, RandomMutationsNeverCrashAndNeverPassWithAWrongCrc) {
  std::mt19937 rng(20261124);
  std::size_t accepted = 0;
  const auto frames = one_of_each();
  for (int i = 0; i < 20000; ++i) {
    auto bytes = encoded(frames[static_cast<std::size_t>(i) % frames.size()]);
    // 1 to 4 edits at distinct positions, each really changing the byte (XOR with non-zero).
    const std::size_t first = rng() % bytes.size();
    const std::size_t edits = 1 + rng() % 4;
    for (std::size_t e = 0; e < edits; ++e) {
      bytes[(first + e * 7) % bytes.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    }
    if (rng() % 4 == 0) {
      bytes.resize(bytes.size() + 4);  // trailing garbage on top
      bytes.back() = static_cast<std::uint8_t>(rng());
    }
    hcp_frame out;
    accepted += decode(bytes, out) == DecodeStatus::kOk ? 1U : 0U;
  }
  // A random edit that keeps the CRC right is a 2^-32 event.
  EXPECT_EQ(accepted, 0U);
}

TEST(Codec, SequenceOrderWrapsAround) {
  EXPECT_TRUE(sequence_newer(2, 1));
  EXPECT_FALSE(sequence_newer(1, 1));
  EXPECT_FALSE(sequence_newer(1, 2));
  EXPECT_TRUE(sequence_newer(0, 0xFFFFFFFFU));
  EXPECT_TRUE(sequence_newer(5, 0xFFFFFFF0U));
  EXPECT_FALSE(sequence_newer(0xFFFFFFF0U, 5));
}

TEST(Codec, StatusNamesAreDistinct) {
  EXPECT_EQ(to_string(DecodeStatus::kBadCrc), "crc");
  EXPECT_NE(to_string(DecodeStatus::kBadMagic), to_string(DecodeStatus::kBadVersion));
}

}  // namespace
}  // namespace hapticctrl::protocol
