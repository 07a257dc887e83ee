#pragma once
// Connection::Impl: the I/O shell around ClientSession (client_session.hpp), which owns the
// protocol. The shell owns the socket, the receive thread, the locks and the waits; every call
// into the session holds session_mutex. Internal to the client library.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "client_session.hpp"
#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/udp_socket.hpp"

namespace hapticctrl::client {

/// The I/O shell around ClientSession: the socket, the receive thread, the locks and the waits.
struct Connection::Impl {
  protocol::UdpSocket socket{protocol::Endpoint::resolve("0.0.0.0", 0)};
  protocol::Endpoint bridge;
  std::atomic<bool> running{true};

  mutable std::mutex session_mutex;  // guards session
  mutable std::condition_variable answer_cv;
  std::condition_variable ack_cv;
  ClientSession session;

  std::mutex call_mutex;  // one reliable exchange at a time
  std::mutex loop_mutex;
  std::function<void(const StateSnapshot&)> on_cycle;
  /// stop_loop() called from inside the callback: the loop ends once the callback returns (the
  /// receive thread holds loop_mutex while it runs).
  std::atomic<bool> loop_stop_requested{false};
  std::thread receiver;

  Impl(const Address& address, ConnectOptions opts)
      : bridge(resolve(address)),
        session(std::move(opts), address.host + ":" + std::to_string(address.port)) {
    handshake();
    receiver = std::thread([this] { receive_loop(); });
  }

  static protocol::Endpoint resolve(const Address& address) {
    try {
      return protocol::Endpoint::resolve(address.host, address.port);
    } catch (const std::exception& e) {
      throw ClientError(ErrorCode::kTransport, e.what());
    }
  }

  ~Impl() {
    running.store(false);
    if (receiver.joinable()) {
      receiver.join();
    }
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  Impl(Impl&&) = delete;
  Impl& operator=(Impl&&) = delete;

  /// Encodes and sends `frame`; touches no session state, so it runs without session_mutex.
  bool transmit(hcp_frame frame) noexcept {  // a copy: the XDR encoder takes it mutable
    protocol::FrameBuffer out;  // NOLINT(cppcoreguidelines-pro-type-member-init): encode() fills it
    const std::size_t n = protocol::encode(frame, out);
    return n != 0 && socket.send_to({out.data(), n}, bridge);
  }

  /// Sends `frame`; the caller holds session_mutex (the session counts the quiet time from it).
  bool send_locked(const hcp_frame& frame) noexcept {
    if (!transmit(frame)) {
      return false;
    }
    session.on_sent(MonotonicClock::now());
    return true;
  }

  /// A datagram from the bridge, decoded; nullopt (counted) for anything else.
  std::optional<hcp_frame> frame_of(const protocol::Received& r, const protocol::FrameBuffer& in,
                                    const protocol::Endpoint& from, bool count_invalid) {
    hcp_frame frame;
    const std::size_t size = r.status == protocol::Received::Status::kDatagram ? r.size : 0;
    if (!(from == bridge) ||
        protocol::decode({in.data(), size}, frame) != protocol::DecodeStatus::kOk) {
      if (count_invalid) {
        const std::lock_guard lock(session_mutex);
        session.on_invalid();
      }
      return std::nullopt;
    }
    return frame;
  }

  // --- handshake ---------------------------------------------------------------------------
  void handshake() {
    const TimePoint deadline = MonotonicClock::now() + session.options().connect_timeout;
    protocol::FrameBuffer in;  // NOLINT(cppcoreguidelines-pro-type-member-init): receive() fills it
    while (MonotonicClock::now() < deadline) {
      if (const auto hello = session.hello_due(MonotonicClock::now())) {
        send_locked(*hello);  // no other thread yet
      }
      protocol::Endpoint from;
      const protocol::Received r = socket.receive(in, from, std::chrono::milliseconds(5));
      if (r.status != protocol::Received::Status::kDatagram) {
        continue;
      }
      const auto frame = frame_of(r, in, from, false);
      if (!frame) {
        continue;
      }
      HandshakeStep step = session.on_handshake_frame(*frame, MonotonicClock::now());
      if (step.reply) {
        send_locked(*step.reply);
      }
      if (step.fail) {
        throw *step.fail;
      }
      if (step.welcomed) {
        return;
      }
    }
    throw session.handshake_timeout();
  }

  // --- receive thread ----------------------------------------------------------------------
  void receive_loop() noexcept {
    protocol::FrameBuffer in;  // NOLINT(cppcoreguidelines-pro-type-member-init): receive() fills it
    while (running.load(std::memory_order_relaxed)) {
      protocol::Endpoint from;
      const protocol::Received r = socket.receive(in, from, std::chrono::milliseconds(5));
      Arrival arrival = Arrival::kIgnored;
      if (r.status == protocol::Received::Status::kDatagram ||
          r.status == protocol::Received::Status::kOversized) {
        if (const auto frame = frame_of(r, in, from, true)) {
          arrival = on_frame(*frame);
        }
      }
      after_receive(arrival);
    }
  }

  Arrival on_frame(const hcp_frame& frame) noexcept {
    const std::lock_guard lock(session_mutex);
    return session.on_frame(frame, MonotonicClock::now());
  }

  /// Wakes whoever waits for what arrived, runs the periodic function on a new state, then
  /// the keepalive and the silence watchdog.
  void after_receive(Arrival arrival) noexcept {
    StateSnapshot state;
    bool closed = arrival == Arrival::kClosed;
    {
      const std::lock_guard lock(session_mutex);
      state = session.latest();
      const TimePoint now = MonotonicClock::now();
      if (const auto keepalive = session.keepalive_due(now)) {
        send_locked(*keepalive);
      }
      closed = session.close_if_silent(now) || closed;  // once per session: not a cycle path
    }
    if (arrival == Arrival::kAnswer) {
      answer_cv.notify_all();
      const std::lock_guard lock(loop_mutex);
      if (on_cycle) {
        on_cycle(state);
      }
      if (loop_stop_requested.exchange(false)) {
        on_cycle = nullptr;
      }
    }
    if (arrival == Arrival::kAck || closed) {
      ack_cv.notify_all();
    }
  }

  /// A control frame the session built (nothing: it refused), sent without holding
  /// session_mutex, so that the receive thread never waits for this send's syscall.
  bool send_control(const std::optional<hcp_frame>& frame) noexcept {
    if (!frame || !transmit(*frame)) {
      return false;
    }
    const std::lock_guard lock(session_mutex);
    session.on_sent(MonotonicClock::now());
    session.on_control_sent();
    return true;
  }

  /// The contact frames due (protocol 1.3), sent after a control frame: at most one round.
  void send_due_contacts() noexcept {
    for (std::size_t i = 0; i <= kMaxContacts; ++i) {
      std::optional<hcp_frame> contact;
      {
        const std::lock_guard lock(session_mutex);
        contact = session.contact_frame_due(MonotonicClock::now());
      }
      if (!contact || !send_control(contact)) {
        break;
      }
    }
  }

  // --- reliable exchange ---------------------------------------------------------------------
  /// Sends the reliable frame `make` builds until the controller acknowledges it.
  template <typename Make>
  void exchange(const std::string& what, Make make) {
    const std::lock_guard call_lock(call_mutex);
    std::unique_lock lock(session_mutex);
    hcp_frame frame = make();
    const std::uint32_t sequence = frame.header.sequence;
    const ConnectOptions& options = session.options();
    const auto deadline = MonotonicClock::now() + options.call_timeout;
    int tries = 0;
    while (MonotonicClock::now() < deadline) {
      frame.header.sender_time_ns = to_ns(MonotonicClock::now());
      send_locked(frame);
      ++tries;
      std::optional<AckOutcome> ack;
      ack_cv.wait_for(lock, options.retransmit_after, [&] {
        ack = session.take_ack(sequence);
        return ack.has_value() || !session.is_open();
      });
      if (!session.is_open()) {
        throw session.closed_error(what);
      }
      if (!ack) {
        continue;
      }
      if (ack->status == HCP_ACK_OK) {
        if (frame.body.type == HCP_PARAM) {
          session.on_param_applied(frame.body.hcp_body_u.param);
        }
        return;
      }
      if (ack->status == HCP_ACK_REJECTED) {
        throw ClientError(ErrorCode::kRejected,
                          what + ": the controller refused the value: " + ack->reason);
      }
      // HCP_ACK_RETRY: the controller's queue was full; the loop sends again.
    }
    throw ClientError(ErrorCode::kTimeout,
                      what + ": no acknowledgement from the controller at " + session.peer_text() +
                          " after " + std::to_string(tries) + " tries in " +
                          std::to_string(options.call_timeout.count()) + " ms");
  }

  void set_param(const hcp_param& param, const std::string& what) {
    exchange(what, [&] { return session.param_frame(param, what); });
  }

  void bye() {
    exchange("close", [&] { return session.bye_frame("close"); });
    const std::lock_guard lock(session_mutex);
    session.close("closed by the application");
  }

  bool is_open() const noexcept {
    const std::lock_guard lock(session_mutex);
    return session.is_open();
  }
};

}  // namespace hapticctrl::client
