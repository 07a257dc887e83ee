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

#include "support/protocol_frames.hpp"

namespace hapticctrl::protocol {
namespace {

using test::kToken;
using test::object_frame;
using test::one_of_each;

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

TEST(Codec, AContactNoSurfaceMakesIsOutOfRange) {  // each rule: values_test.cpp
  hcp_frame f = make_frame(HCP_CONTROL_CONTACT, kToken, 1, 1);
  f.body.hcp_body_u.contact.slots = pack_contact_slots(0, 1);
  f.body.hcp_body_u.contact.contact.normal[2] = 0.5F;  // not a unit normal
  f.body.hcp_body_u.contact.contact.stiffness = 1000.0F;
  hcp_frame out;
  EXPECT_EQ(decode(with_valid_crc(f), out), DecodeStatus::kOutOfRange);
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
