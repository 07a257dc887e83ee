// Implements codec.hpp: encoding and decoding of hapticctrl protocol frames
// (protocol/hapticctrl_protocol.x).
#include "hapticctrl/protocol/codec.hpp"

#include <rpc/xdr.h>
#include <zlib.h>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::protocol {
namespace {

constexpr std::size_t kCrcBytes = 4;

std::uint32_t crc_of(const std::uint8_t* data, std::size_t length) noexcept {
  return static_cast<std::uint32_t>(
      ::crc32(0UL, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(length)));
}

std::uint32_t read_be32(const std::uint8_t* p) noexcept {
  return (std::uint32_t{p[0]} << 24U) | (std::uint32_t{p[1]} << 16U) | (std::uint32_t{p[2]} << 8U) |
         std::uint32_t{p[3]};
}

void write_be32(std::uint8_t* p, std::uint32_t v) noexcept {
  p[0] = static_cast<std::uint8_t>(v >> 24U);
  p[1] = static_cast<std::uint8_t>(v >> 16U);
  p[2] = static_cast<std::uint8_t>(v >> 8U);
  p[3] = static_cast<std::uint8_t>(v);
}

/// Frames whose layout is frozen across versions, so they decode whatever the peer's major.
bool version_independent(hcp_frame_type type) noexcept {
  return type == HCP_HELLO || type == HCP_REFUSE;
}

}  // namespace

std::string_view to_string(DecodeStatus status) noexcept {
  switch (status) {
    case DecodeStatus::kOk:
      return "ok";
    case DecodeStatus::kBadSize:
      return "size";
    case DecodeStatus::kBadMagic:
      return "magic";
    case DecodeStatus::kBadCrc:
      return "crc";
    case DecodeStatus::kBadVersion:
      return "version";
    case DecodeStatus::kMalformed:
      return "malformed";
    case DecodeStatus::kOutOfRange:
      return "range";
  }
  return "unknown";
}

hcp_frame make_frame(hcp_frame_type type, std::uint64_t token, std::uint32_t sequence,
                     std::int64_t sender_time_ns) noexcept {
  hcp_frame frame{};
  frame.header.magic = HCP_MAGIC;
  frame.header.protocol = kVersion;
  frame.header.token = token;
  frame.header.sequence = sequence;
  frame.header.sender_time_ns = sender_time_ns;
  frame.body.type = type;
  return frame;
}

std::size_t encode(hcp_frame& frame, std::span<std::uint8_t> out) noexcept {
  XDR xdrs;
  // xdrmem never writes past the given size; the cast is the C API's (it takes char*).
  xdrmem_create(&xdrs, reinterpret_cast<char*>(out.data()), static_cast<u_int>(out.size()),
                XDR_ENCODE);
  frame.crc32 = 0;
  const bool ok = xdr_hcp_frame(&xdrs, &frame) != 0;
  const std::size_t length = ok ? xdr_getpos(&xdrs) : 0;
  xdr_destroy(&xdrs);
  if (length < kMinFrameBytes || length > kMaxFrameBytes) {
    return 0;
  }
  frame.crc32 = crc_of(out.data(), length - kCrcBytes);
  write_be32(out.data() + length - kCrcBytes, frame.crc32);
  return length;
}

DecodeStatus decode(std::span<const std::uint8_t> bytes, hcp_frame& frame) noexcept {
  if (bytes.size() < kMinFrameBytes || bytes.size() > kMaxFrameBytes || bytes.size() % 4 != 0) {
    return DecodeStatus::kBadSize;
  }
  if (read_be32(bytes.data()) != HCP_MAGIC) {
    return DecodeStatus::kBadMagic;
  }
  const std::size_t body_end = bytes.size() - kCrcBytes;
  if (crc_of(bytes.data(), body_end) != read_be32(bytes.data() + body_end)) {
    return DecodeStatus::kBadCrc;
  }
  XDR xdrs;
  // XDR_DECODE only reads through the pointer; the C API is not const-correct.
  xdrmem_create(&xdrs, const_cast<char*>(reinterpret_cast<const char*>(bytes.data())),
                static_cast<u_int>(bytes.size()), XDR_DECODE);
  frame = hcp_frame{};
  const bool header_ok = xdr_hcp_header(&xdrs, &frame.header) != 0;
  const bool other_major =
      header_ok && version_major(frame.header.protocol) != version_major(kVersion);
  bool frame_ok = false;
  if (header_ok) {
    xdr_setpos(&xdrs, 0);
    frame_ok = xdr_hcp_frame(&xdrs, &frame) != 0 && xdr_getpos(&xdrs) == bytes.size();
  }
  xdr_destroy(&xdrs);
  if (other_major && !(frame_ok && version_independent(frame.body.type))) {
    return DecodeStatus::kBadVersion;
  }
  if (!frame_ok) {
    return DecodeStatus::kMalformed;
  }
  if (check_body(frame.body)) {
    return DecodeStatus::kOutOfRange;
  }
  return DecodeStatus::kOk;
}

}  // namespace hapticctrl::protocol
