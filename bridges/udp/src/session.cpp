// The UDP bridge's session: each datagram to its part (the handshake gate, the parameter
// channel, the control intake), and the session's life (open, watchdog, close, BYE). Parameters
// are in session_parameters.cpp, the answer side in session_answer.cpp.
#include "hapticctrl/udp_bridge/session.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <utility>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::udp_bridge {
namespace {

using protocol::DecodeStatus;
using shm::LinkDrop;

shm::VprPayload fresh_vpr(std::uint64_t session_number) noexcept {
  shm::VprPayload v;
  v.session_id = session_number;
  return v;
}

}  // namespace

LinkDrop drop_reason_of(DecodeStatus status) noexcept {
  switch (status) {
    case DecodeStatus::kBadSize:
      return LinkDrop::kSize;
    case DecodeStatus::kBadMagic:
      return LinkDrop::kMagic;
    case DecodeStatus::kBadCrc:
      return LinkDrop::kCrc;
    case DecodeStatus::kBadVersion:
      return LinkDrop::kVersion;
    case DecodeStatus::kOutOfRange:
      return LinkDrop::kRange;
    case DecodeStatus::kMalformed:
    case DecodeStatus::kOk:
      break;
  }
  return LinkDrop::kMalformed;
}

Session::Session(SessionSettings settings, std::function<std::uint64_t()> random_token)
    : settings_(std::move(settings)),
      random_token_(std::move(random_token)),
      hello_limiter_(settings_.hello_limits) {
  view_.publish_quietly(session_, 0);
}

void Session::set_controller(const ControllerPorts* ports, TimePoint now) noexcept {
  if (session_.token != 0) {
    end_session(now);
  }
  have_controller_ = ports != nullptr && ports->vpr != nullptr;
  ports_ = have_controller_ ? *ports : ControllerPorts{};
}

void Session::on_oversized() noexcept {
  counters_.frames_in.fetch_add(1, std::memory_order_relaxed);
  counters_.drop(LinkDrop::kSize);
}

std::size_t Session::on_datagram(std::span<const std::uint8_t> bytes,
                                 const protocol::Endpoint& from, TimePoint now,
                                 std::span<std::uint8_t> reply) noexcept {
  counters_.frames_in.fetch_add(1, std::memory_order_relaxed);
  const std::uint32_t source = ntohl(from.address.sin_addr.s_addr);
  if (!settings_.allowed_clients.allows(source)) {
    counters_.drop(LinkDrop::kNotAllowed);  // not even decoded
    return 0;
  }
  hcp_frame in;
  const DecodeStatus status = protocol::decode(bytes, in);
  // A PARAM with a bad value from the session is answered (REJECTED), and a HELLO asking for
  // out-of-range values is refused (BAD_REQUEST, as the .x says), not silently dropped.
  const bool out_of_range = status == DecodeStatus::kOutOfRange;
  const bool param_out_of_range = out_of_range && in.body.type == HCP_PARAM;
  const bool hello_out_of_range = out_of_range && in.body.type == HCP_HELLO;
  if (status != DecodeStatus::kOk && !param_out_of_range && !hello_out_of_range) {
    counters_.drop(drop_reason_of(status));
    return 0;
  }
  switch (in.body.type) {
    case HCP_HELLO:
      if (!hello_limiter_.admit(source, now)) {
        counters_.drop(LinkDrop::kRateLimited);
        return 0;
      }
      if (hello_out_of_range) {
        counters_.drop(LinkDrop::kRange);  // no session for it: counted, and told why
        const protocol::Problem why = protocol::check_hello(in.body.hcp_body_u.hello);
        return refuse(HCP_REFUSE_BAD_REQUEST, in.header.protocol, 0,
                      why ? *why : std::string_view("HELLO values out of range"), now, reply);
      }
      return on_hello(in, from, now, reply);
    case HCP_CONTROL_OBJECT:
    case HCP_CONTROL_OBJECT_TIMED:
    case HCP_CONTROL_WRENCH:
    case HCP_CONTROL_WRENCH_TIMED:
    case HCP_CONTROL_CONTACT:
    case HCP_CONTROL_JOINT_TARGET:
    case HCP_CONTROL_JOINT_TORQUE:
    case HCP_KEEPALIVE:
      if (!from_session(in, from, session_) || !negotiated(in.body.type, session_.features)) {
        counters_.drop(LinkDrop::kToken);
        return 0;
      }
      on_control(in, now);
      return 0;
    case HCP_PARAM:
      if (!from_session(in, from, session_)) {
        counters_.drop(LinkDrop::kToken);
        return 0;
      }
      return on_param(in, !param_out_of_range, now, reply);
    case HCP_BYE:
      if (!from_session(in, from, session_)) {
        counters_.drop(LinkDrop::kToken);
        return 0;
      }
      return on_bye(in, now, reply);
    case HCP_REFUSE:  // the client refuses our WELCOME (no common version): end its session
      if (from_session(in, from, session_)) {
        end_session(now);
      } else {
        counters_.drop(LinkDrop::kToken);
      }
      return 0;
    case HCP_WELCOME:
    case HCP_ANSWER:
    case HCP_ANSWER_TIMED:
    case HCP_ANSWER_COUPLED:
    case HCP_ACK:
      break;
  }
  counters_.drop(LinkDrop::kUnexpected);
  return 0;
}

std::size_t Session::on_hello(const hcp_frame& in, const protocol::Endpoint& from, TimePoint now,
                              std::span<std::uint8_t> reply) noexcept {
  const HelloVerdict verdict =
      judge_hello(in, from, {session_, have_controller_, now - last_heard_, watchdog_ms_});
  switch (verdict.kind) {
    case HelloVerdict::Kind::kOpen:
      open(in, from, now);
      return welcome(now, reply);
    case HelloVerdict::Kind::kWelcomeAgain:
      last_heard_ = now;
      return welcome(now, reply);
    case HelloVerdict::Kind::kRefuse:
      break;
  }
  if (verdict.code == HCP_REFUSE_VERSION) {
    counters_.refused_version.fetch_add(1, std::memory_order_relaxed);
  } else if (verdict.code == HCP_REFUSE_BUSY) {
    counters_.refused_busy.fetch_add(1, std::memory_order_relaxed);
  }
  return refuse(verdict.code, in.header.protocol, verdict.retry_ms, verdict.reason, now, reply);
}

void Session::open(const hcp_frame& hello, const protocol::Endpoint& from, TimePoint now) noexcept {
  std::uint64_t token = 0;
  while (token == 0) {
    token = random_token_();
  }
  const hcp_hello& asked = hello.body.hcp_body_u.hello;
  session_.token = token;
  session_.peer = from;
  session_.features = granted_features(asked.features);
  watchdog_ms_ = granted_watchdog_ms(asked.watchdog_ms, settings_.default_watchdog_ms,
                                     settings_.max_watchdog_ms);
  last_heard_ = now;
  engaged_ = false;
  params_.reset();
  ingest_.reset();
  control_received_ = 0;
  control_received_shared_.store(0, std::memory_order_relaxed);
  link_view_.publish_quietly({}, 0);
  vpr_ = fresh_vpr(++session_number_);
  vpr_.watchdog_timeout_us = watchdog_ms_ * 1000U;
  if ((session_.features & HCP_FEATURE_LOCAL_COUPLING) != 0) {
    vpr_.flags |= shm::vpr_flags::kLocalCoupling;
  }
  publish_vpr(now);
  publish_view();
  counters_.sessions_opened.fetch_add(1, std::memory_order_relaxed);
}

void Session::end_session(TimePoint now) noexcept {
  session_ = SessionView{};
  publish_view();
  vpr_ = fresh_vpr(0);  // session 0: the core renders nothing and ramps any wrench out
  publish_vpr(now);
}

std::size_t Session::close(TimePoint now, std::string_view why, std::span<std::uint8_t> notice,
                           protocol::Endpoint& to) noexcept {
  if (session_.token == 0) {
    return 0;
  }
  to = session_.peer;
  const std::size_t n =
      refuse(HCP_REFUSE_NO_CONTROLLER, protocol::kVersion, 0, why, now, notice, session_.token);
  end_session(now);
  return n;
}

bool Session::check_watchdog(TimePoint now) noexcept {
  // A session that sent nothing since its HELLO is held no longer than the default.
  const std::uint32_t limit_ms =
      engaged_ ? watchdog_ms_ : std::min(watchdog_ms_, settings_.default_watchdog_ms);
  if (session_.token == 0 || now - last_heard_ <= std::chrono::milliseconds(limit_ms)) {
    return false;
  }
  counters_.watchdog_expiries.fetch_add(1, std::memory_order_relaxed);
  end_session(now);
  return true;
}

void Session::on_control(const hcp_frame& in, TimePoint now) noexcept {
  if (!ingest_.admit(in.header.sequence)) {
    counters_.drop(LinkDrop::kSequence);
    return;
  }
  last_heard_ = now;
  engaged_ = true;
  if (in.body.type == HCP_KEEPALIVE) {
    return;  // feeds the watchdog only: the core keeps judging the freshness of client data
  }
  ingest_.take(in, now, vpr_);
  link_view_.publish_quietly(ingest_.link(), to_ns(now));
  publish_vpr(now);
  ++control_received_;
  control_received_shared_.store(control_received_, std::memory_order_relaxed);
  counters_.control_accepted.fetch_add(1, std::memory_order_relaxed);
}

std::size_t Session::on_bye(const hcp_frame& in, TimePoint now,
                            std::span<std::uint8_t> reply) noexcept {
  const std::size_t n = ack(ParamAck{in.header.sequence, HCP_ACK_OK}, now, reply);  // session token
  counters_.sessions_closed.fetch_add(1, std::memory_order_relaxed);
  end_session(now);
  return n;
}

std::size_t Session::refuse(hcp_refuse_code code, std::uint32_t peer_version,
                            std::uint32_t retry_ms, std::string_view reason, TimePoint now,
                            std::span<std::uint8_t> reply, std::uint64_t token) noexcept {
  hcp_frame out = protocol::make_frame(HCP_REFUSE, token, ++reply_sequence_, to_ns(now));
  hcp_refuse& r = out.body.hcp_body_u.refuse;
  r.code = code;
  r.peer_version = peer_version;
  r.retry_after_ms = retry_ms;
  protocol::set_text(r.reason, reason);
  return protocol::encode(out, reply);
}

std::size_t Session::welcome(TimePoint now, std::span<std::uint8_t> reply) noexcept {
  hcp_frame out = protocol::make_frame(HCP_WELCOME, session_.token, ++reply_sequence_, to_ns(now));
  hcp_welcome& w = out.body.hcp_body_u.welcome;
  w.features = session_.features;
  w.watchdog_ms = watchdog_ms_;
  w.period_ns = to_ns(ports_.period);
  w.cycle = ports_.heartbeat_cycle != nullptr
                ? ports_.heartbeat_cycle->load(std::memory_order_acquire)
                : 0;
  return protocol::encode(out, reply);
}

void Session::publish_vpr(TimePoint now) noexcept {
  if (ports_.vpr != nullptr) {
    vpr_.received_time_ns = to_ns(now);
    ports_.vpr->publish_quietly(vpr_, to_ns(now));  // the core polls VPr once per cycle
  }
}

void Session::publish_view() noexcept {
  view_.publish_quietly(session_, 0);
}

}  // namespace hapticctrl::udp_bridge
