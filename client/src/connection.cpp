#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/protocol/monotonic_clock.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "channel_passivity.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/timing.hpp"
#include "hapticctrl/protocol/udp_socket.hpp"
#include "hapticctrl/protocol/values.hpp"
#include "link_monitor.hpp"

namespace hapticctrl::client {
namespace {

using protocol::Endpoint;
using protocol::FrameBuffer;
using protocol::monotonic_ns;
using protocol::Received;

std::string version_text(std::uint32_t v) {
  return std::to_string(protocol::version_major(v)) + "." +
         std::to_string(protocol::version_minor(v));
}

}  // namespace

Address Address::parse(std::string_view text) {
  std::string_view rest = text;
  constexpr std::string_view kScheme = "udpxdr://";
  if (rest.substr(0, kScheme.size()) == kScheme) {
    rest.remove_prefix(kScheme.size());
  }
  Address a;
  const std::size_t sep = rest.find_last_of("#:");
  a.host = std::string(rest.substr(0, sep));
  if (sep != std::string_view::npos) {
    const std::string_view port = rest.substr(sep + 1);
    unsigned value = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (ec != std::errc{} || end != port.data() + port.size() || value == 0 || value > 65535) {
      throw ClientError(ErrorCode::kInvalidArgument,
                        "bad controller address '" + std::string(text) +
                            "': expected udpxdr://host:port or host#port with a port 1-65535");
    }
    a.port = static_cast<std::uint16_t>(value);
  }
  if (a.host.empty()) {
    throw ClientError(ErrorCode::kInvalidArgument,
                      "bad controller address '" + std::string(text) + "': no host");
  }
  return a;
}

struct Connection::Impl {
  ConnectOptions options;
  std::string peer_text;
  protocol::UdpSocket socket{Endpoint::resolve("0.0.0.0", 0)};
  Endpoint bridge;
  std::uint64_t token = 0;
  std::uint32_t features = 0;
  std::atomic<std::uint32_t> watchdog{0};  // read by the keepalive, changed by set_watchdog
  std::uint32_t controller_version = 0;
  std::int64_t period_ns = 0;

  std::atomic<std::uint32_t> control_sequence{0};
  std::atomic<std::uint32_t> reliable_sequence{0};
  std::atomic<std::uint64_t> control_sent{0};
  std::atomic<std::int64_t> last_send_ns{0};
  std::atomic<bool> open{false};
  std::atomic<std::int64_t> last_heard_ns{0};  // last valid frame from the bridge
  std::atomic<bool> running{true};

  mutable std::mutex state_mutex;
  mutable std::condition_variable answer_cv;
  StateSnapshot latest;
  LinkMonitor monitor;
  ChannelPassivity passivity;    // under state_mutex
  hcp_coupling_report report{};  // the controller's, from the newest ANSWER_TIMED
  std::int64_t last_object_send_ns = 0;

  std::mutex call_mutex;  // one reliable exchange at a time
  std::mutex ack_mutex;
  std::condition_variable ack_cv;
  bool ack_ready = false;
  std::uint32_t ack_sequence = 0;
  hcp_ack_status ack_status = HCP_ACK_OK;
  std::string ack_reason;
  std::string closed_reason;  // set when the bridge ends the session (guarded by ack_mutex)

  std::mutex loop_mutex;
  std::function<void(const StateSnapshot&)> on_cycle;
  std::thread receiver;

  Impl(const Address& address, ConnectOptions opts)
      : options(std::move(opts)),
        peer_text(address.host + ":" + std::to_string(address.port)),
        bridge(resolve(address)) {
    handshake();
    monitor.set_period(period_ns);
    last_heard_ns.store(monotonic_ns(), std::memory_order_relaxed);
    open.store(true);
    receiver = std::thread([this] { receive_loop(); });
  }

  static Endpoint resolve(const Address& address) {
    try {
      return Endpoint::resolve(address.host, address.port);
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

  bool send(hcp_frame& frame) noexcept {
    FrameBuffer out;  // NOLINT(cppcoreguidelines-pro-type-member-init): encode() fills it
    const std::size_t n = protocol::encode(frame, out);
    if (n == 0 || !socket.send_to({out.data(), n}, bridge)) {
      return false;
    }
    last_send_ns.store(monotonic_ns(), std::memory_order_relaxed);
    return true;
  }

  // --- handshake ---------------------------------------------------------------------------
  void handshake() {
    const std::uint32_t version =
        options.advertised_version != 0 ? options.advertised_version : protocol::kVersion;
    const std::uint32_t min_version =
        options.advertised_min_version != 0 ? options.advertised_min_version : version;
    const std::int64_t deadline = monotonic_ns() + options.connect_timeout.count() * 1'000'000;
    std::string last_refusal;
    ErrorCode last_code = ErrorCode::kTimeout;
    std::int64_t next_hello = 0;
    std::uint32_t sequence = 0;
    FrameBuffer in;  // NOLINT(cppcoreguidelines-pro-type-member-init): receive() fills it
    while (monotonic_ns() < deadline) {
      const std::int64_t now = monotonic_ns();
      if (now >= next_hello) {
        hcp_frame hello = protocol::make_frame(HCP_HELLO, 0, ++sequence, now);
        hello.header.protocol = version;
        hcp_hello& h = hello.body.hcp_body_u.hello;
        h.min_version = min_version;
        h.features = protocol::kAllFeatures;
        h.watchdog_ms = options.watchdog_ms;
        protocol::set_text(h.client_name, options.client_name);
        send(hello);
        next_hello = now + options.retransmit_after.count() * 1'000'000 * 2;
      }
      Endpoint from;
      const Received r = socket.receive(in, from, std::chrono::milliseconds(5));
      if (r.status != Received::Status::kDatagram || !(from == bridge)) {
        continue;
      }
      hcp_frame frame;
      if (protocol::decode({in.data(), r.size}, frame) != protocol::DecodeStatus::kOk) {
        continue;
      }
      if (frame.body.type == HCP_REFUSE) {
        const hcp_refuse& refusal = frame.body.hcp_body_u.refuse;
        last_refusal = std::string(protocol::text_of(refusal.reason));
        if (refusal.code == HCP_REFUSE_VERSION) {
          throw ClientError(ErrorCode::kVersion,
                            "controller at " + peer_text + " refused the connection: " +
                                last_refusal + " (this client speaks " + version_text(version) +
                                ", the controller " + version_text(frame.header.protocol) + ")");
        }
        if (refusal.code == HCP_REFUSE_BAD_REQUEST) {  // asking again would not help
          throw ClientError(ErrorCode::kRejected, "controller at " + peer_text +
                                                      " refused the connection: " + last_refusal);
        }
        last_code = refusal.code == HCP_REFUSE_BUSY ? ErrorCode::kBusy : ErrorCode::kNoController;
        const std::int64_t wait_ns =
            std::max<std::int64_t>(options.retransmit_after.count(), refusal.retry_after_ms) *
            1'000'000;
        next_hello = monotonic_ns() + wait_ns;  // ask again once the other session may be gone
        continue;
      }
      if (frame.body.type != HCP_WELCOME) {
        continue;
      }
      if (protocol::version_major(frame.header.protocol) != protocol::version_major(version)) {
        refuse_welcome(frame, version);
      }
      token = frame.header.token;
      features = frame.body.hcp_body_u.welcome.features;
      watchdog.store(frame.body.hcp_body_u.welcome.watchdog_ms);
      period_ns = frame.body.hcp_body_u.welcome.period_ns;
      controller_version = frame.header.protocol;
      return;
    }
    if (last_refusal.empty()) {
      throw ClientError(ErrorCode::kTimeout, "no answer from a hapticctrl controller at " +
                                                 peer_text + " within " +
                                                 std::to_string(options.connect_timeout.count()) +
                                                 " ms: is hapticctrl-udp running there?");
    }
    throw ClientError(last_code, "controller at " + peer_text + " refused the connection for " +
                                     std::to_string(options.connect_timeout.count()) +
                                     " ms: " + last_refusal);
  }

  [[noreturn]] void refuse_welcome(const hcp_frame& welcome, std::uint32_t version) {
    const std::string reason = "protocol version mismatch: client " + version_text(version) +
                               ", controller " + version_text(welcome.header.protocol);
    hcp_frame refusal = protocol::make_frame(HCP_REFUSE, welcome.header.token, 1, monotonic_ns());
    refusal.header.protocol = version;
    refusal.body.hcp_body_u.refuse.code = HCP_REFUSE_VERSION;
    refusal.body.hcp_body_u.refuse.peer_version = welcome.header.protocol;
    protocol::set_text(refusal.body.hcp_body_u.refuse.reason, reason);
    send(refusal);
    throw ClientError(ErrorCode::kVersion, "connection to " + peer_text + " refused: " + reason);
  }

  // --- receive thread ----------------------------------------------------------------------
  void receive_loop() noexcept {
    FrameBuffer in;  // NOLINT(cppcoreguidelines-pro-type-member-init): receive() fills it
    while (running.load(std::memory_order_relaxed)) {
      Endpoint from;
      const Received r = socket.receive(in, from, std::chrono::milliseconds(5));
      const std::int64_t now = monotonic_ns();
      if (r.status == Received::Status::kDatagram || r.status == Received::Status::kOversized) {
        handle_datagram({in.data(), r.status == Received::Status::kDatagram ? r.size : 0}, from,
                        now);
      }
      keep_alive(now);
      close_if_silent(now);
    }
  }

  /// A session whose bridge sends nothing at all (no answer, no refusal) for `answer_timeout` is
  /// over: the bridge was killed, or lost its controller without a word.
  void close_if_silent(std::int64_t now) noexcept {
    const auto limit_ns = std::chrono::nanoseconds(options.answer_timeout).count();
    if (limit_ns == 0 || !open.load(std::memory_order_relaxed) ||
        now - last_heard_ns.load(std::memory_order_relaxed) <= limit_ns) {
      return;
    }
    // Once per session: not a cycle path.
    close_session("no answer from the bridge for " +
                  std::to_string(options.answer_timeout.count()) + " ms");
  }

  /// Marks the session closed for `reason` and wakes whoever waits for an acknowledgement.
  void close_session(std::string_view reason) noexcept {
    {
      const std::lock_guard lock(ack_mutex);
      closed_reason.assign(reason);
    }
    open.store(false);
    ack_cv.notify_all();
  }

  void handle_datagram(std::span<const std::uint8_t> bytes, const Endpoint& from,
                       std::int64_t now) noexcept {
    hcp_frame frame;
    if (!(from == bridge) || protocol::decode(bytes, frame) != protocol::DecodeStatus::kOk ||
        frame.header.token != token) {
      const std::lock_guard lock(state_mutex);
      monitor.on_invalid();
      return;
    }
    last_heard_ns.store(now, std::memory_order_relaxed);
    if (frame.body.type == HCP_ANSWER || frame.body.type == HCP_ANSWER_TIMED) {
      handle_answer(frame, now);
    } else if (frame.body.type == HCP_REFUSE) {  // the bridge ended the session, and says why
      close_session(protocol::text_of(frame.body.hcp_body_u.refuse.reason));
    } else if (frame.body.type == HCP_ACK) {
      const hcp_ack& a = frame.body.hcp_body_u.ack;
      {
        const std::lock_guard lock(ack_mutex);
        ack_ready = true;
        ack_sequence = a.acked_sequence;
        ack_status = a.status;
        ack_reason.assign(protocol::text_of(a.reason));  // not a per-cycle path
      }
      ack_cv.notify_all();
    }
  }

  void handle_answer(const hcp_frame& frame, std::int64_t now) noexcept {
    const bool timed = frame.body.type == HCP_ANSWER_TIMED;
    const hcp_answer& a =
        timed ? frame.body.hcp_body_u.answer_timed.answer : frame.body.hcp_body_u.answer;
    StateSnapshot s;
    {
      const std::lock_guard lock(state_mutex);
      if (!monitor.on_answer(frame.header.sequence, now, a.echo_sequence, a.echo_time_ns,
                             a.control_received)) {
        return;
      }
      s.valid = true;
      s.cycle = a.cycle;
      s.received_ns = now;
      s.state_word = a.state_word;
      s.core_state = a.core_state;
      s.stop_reason = a.stop_reason;
      s.command_type = static_cast<CommandType>(a.command_type);
      protocol::from_wire(a.coupling_wrench, s.coupling_wrench);
      if (timed) {
        // Two-port passivity, this end: the application gets the wrench with the PC's damper.
        report = frame.body.hcp_body_u.answer_timed.coupling;
        passivity.on_controller_energy(report.energy_in);
        passivity.on_coupling_damping(report.gains[1], report.gains[3]);
        s.coupling_wrench = passivity.render(s.coupling_wrench);
      }
      protocol::from_wire(a.handle_pose, s.handle_pose);
      protocol::from_wire(a.handle_twist, s.handle_twist);
      protocol::from_wire(a.joint_position, s.joint_position);
      protocol::from_wire(a.joint_velocity, s.joint_velocity);
      latest = s;
    }
    answer_cv.notify_all();
    const std::lock_guard lock(loop_mutex);
    if (on_cycle) {
      on_cycle(s);
    }
  }

  /// Protocol 1.1: the object state with an echo of the newest answer, from which the bridge
  /// measures the link and the core the coupling loop (docs/protocol.md).
  bool send_timed_object(const Pose7& pose, const Vector6& twist, std::int64_t now) noexcept {
    bool have_answer = false;
    std::uint64_t cycle = 0;
    std::int64_t held = 0;
    std::uint32_t energy = 0;
    {
      const std::lock_guard lock(state_mutex);
      have_answer = latest.valid;
      cycle = latest.cycle;
      held = now - latest.received_ns;
      // The step the application just took, under the wrench it got (at most 0.1 s counted).
      if (last_object_send_ns != 0) {
        const double dt = std::min(0.1, static_cast<double>(now - last_object_send_ns) * 1e-9);
        passivity.on_step(twist, dt);
      }
      last_object_send_ns = now;
      energy = passivity.energy_in_uj();
    }
    hcp_frame f =
        protocol::make_frame(HCP_CONTROL_OBJECT_TIMED, token, next_control_sequence(), now);
    hcp_control_object_timed& o = f.body.hcp_body_u.timed;
    for (std::size_t i = 0; i < 3; ++i) {
      o.position[i] = static_cast<float>(pose[i]);
    }
    const protocol::PackedRotation r =
        protocol::pack_rotation({pose[3], pose[4], pose[5], pose[6]});
    o.rotation[0] = r[0];
    o.rotation[1] = r[1];
    protocol::to_wire(twist, o.twist);
    o.answer_echo = protocol::pack_answer_echo(cycle, held, have_answer);
    o.energy_in = energy;
    return send_control(f);
  }

  void keep_alive(std::int64_t now) noexcept {
    const std::int64_t quiet_ns =
        static_cast<std::int64_t>(watchdog.load(std::memory_order_relaxed)) * 1'000'000 / 4;
    if (options.keepalive && open.load(std::memory_order_relaxed) &&
        now - last_send_ns.load(std::memory_order_relaxed) > quiet_ns) {
      hcp_frame k = protocol::make_frame(HCP_KEEPALIVE, token, next_control_sequence(), now);
      send(k);
    }
  }

  std::uint32_t next_control_sequence() noexcept {
    return control_sequence.fetch_add(1, std::memory_order_relaxed) + 1;
  }

  bool send_control(hcp_frame& frame) noexcept {
    if (!open.load(std::memory_order_relaxed) || protocol::check_control(frame.body)) {
      return false;
    }
    if (!send(frame)) {
      return false;
    }
    control_sent.fetch_add(1, std::memory_order_relaxed);
    return true;
  }

  // --- reliable exchange ---------------------------------------------------------------------
  void exchange(hcp_frame& frame, const std::string& what) {
    const std::lock_guard call_lock(call_mutex);
    if (!open.load()) {
      throw closed_error(what);
    }
    frame.header.token = token;
    frame.header.sequence = reliable_sequence.fetch_add(1) + 1;
    const std::uint32_t sequence = frame.header.sequence;
    const auto deadline = std::chrono::steady_clock::now() + options.call_timeout;
    int tries = 0;
    while (std::chrono::steady_clock::now() < deadline) {
      frame.header.sender_time_ns = monotonic_ns();
      send(frame);
      ++tries;
      std::unique_lock lock(ack_mutex);
      if (!ack_cv.wait_for(lock, options.retransmit_after, [&] {
            return (ack_ready && ack_sequence == sequence) || !open.load();
          })) {
        continue;
      }
      if (!open.load()) {
        lock.unlock();
        throw closed_error(what);
      }
      ack_ready = false;
      if (ack_status == HCP_ACK_OK) {
        return;
      }
      if (ack_status == HCP_ACK_REJECTED) {
        throw ClientError(ErrorCode::kRejected,
                          what + ": the controller refused the value: " + ack_reason);
      }
      // HCP_ACK_RETRY: the controller's queue was full; the loop sends again.
    }
    throw ClientError(ErrorCode::kTimeout,
                      what + ": no acknowledgement from the controller at " + peer_text +
                          " after " + std::to_string(tries) + " tries in " +
                          std::to_string(options.call_timeout.count()) + " ms");
  }

  ClientError closed_error(const std::string& what) {
    const std::lock_guard lock(ack_mutex);
    return {ErrorCode::kClosed, what + ": the session is closed" +
                                    (closed_reason.empty() ? "" : " (" + closed_reason + ")")};
  }

  void set_param(hcp_param param, const std::string& what) {
    if (const auto problem = protocol::check_param(param)) {
      throw ClientError(ErrorCode::kInvalidArgument, what + ": " + std::string(*problem));
    }
    hcp_frame frame = protocol::make_frame(HCP_PARAM, token, 0, 0);
    frame.body.hcp_body_u.param = param;
    exchange(frame, what);
    if (param.id == HCP_P_WATCHDOG) {
      watchdog.store(param.hcp_param_u.watchdog_ms);
    }
  }

  void bye() {
    hcp_frame frame = protocol::make_frame(HCP_BYE, token, 0, 0);
    exchange(frame, "close");
    open.store(false);
  }
};

Connection::Connection(const Address& address, const ConnectOptions& options)
    : impl_(std::make_unique<Impl>(address, options)) {}
Connection::Connection(Connection&&) noexcept = default;
Connection& Connection::operator=(Connection&&) noexcept = default;

Connection::~Connection() {
  if (impl_ && impl_->open.load()) {
    try {
      impl_->bye();
    } catch (const ClientError&) {  // best effort: the bridge's watchdog closes it otherwise
    }
  }
}

void Connection::close() {
  if (impl_->open.load()) {
    impl_->bye();
  }
}

namespace {
/// The first protocol version with the _SP frame parameters.
constexpr std::uint32_t kSinglePrecisionFrames = protocol::make_version(1, 2);

hcp_param param_of(hcp_param_id id) {
  hcp_param p{};
  p.id = id;
  return p;
}
}  // namespace

void Connection::set_time_step(double seconds) {
  hcp_param p = param_of(HCP_P_TIME_STEP);
  p.hcp_param_u.time_step = seconds;
  impl_->set_param(p, "set_time_step");
}
void Connection::set_force_factor(double factor) {
  hcp_param p = param_of(HCP_P_FORCE_FACTOR);
  p.hcp_param_u.force_factor = factor;
  impl_->set_param(p, "set_force_factor");
  const std::lock_guard lock(impl_->state_mutex);
  impl_->passivity.set_force_factor(factor);
}
void Connection::set_speed_factor(double factor) {
  hcp_param p = param_of(HCP_P_SPEED_FACTOR);
  p.hcp_param_u.speed_factor = factor;
  impl_->set_param(p, "set_speed_factor");
  const std::lock_guard lock(impl_->state_mutex);
  impl_->passivity.set_speed_factor(factor);
}
// A 1.2 controller gets frames in single precision (PARAM 68 bytes, within the 90 of control
// frames); a 1.1 one the double form it knows (96 bytes).
void Connection::set_base_frame(const Pose7& frame) {
  hcp_param p{};
  if (impl_->controller_version >= kSinglePrecisionFrames) {
    p = param_of(HCP_P_BASE_FRAME_SP);
    protocol::to_wire(frame, p.hcp_param_u.base_frame_sp);
  } else {
    p = param_of(HCP_P_BASE_FRAME);
    protocol::to_wire(frame, p.hcp_param_u.base_frame);
  }
  impl_->set_param(p, "set_base_frame");
}
void Connection::set_observation_frame(const Pose7& frame) {
  hcp_param p{};
  if (impl_->controller_version >= kSinglePrecisionFrames) {
    p = param_of(HCP_P_OBSERVATION_FRAME_SP);
    protocol::to_wire(frame, p.hcp_param_u.observation_frame_sp);
  } else {
    p = param_of(HCP_P_OBSERVATION_FRAME);
    protocol::to_wire(frame, p.hcp_param_u.observation_frame);
  }
  impl_->set_param(p, "set_observation_frame");
}
void Connection::set_indexing_mode(IndexingMode mode) {
  hcp_param p = param_of(HCP_P_INDEXING_MODE);
  p.hcp_param_u.indexing_mode = static_cast<std::uint32_t>(mode);
  impl_->set_param(p, "set_indexing_mode");
}
void Connection::set_command_type(CommandType type) {
  hcp_param p = param_of(HCP_P_COMMAND_TYPE);
  p.hcp_param_u.command_type = static_cast<std::uint32_t>(type);
  impl_->set_param(p, "set_command_type");
}
void Connection::attach_object(double mass, const std::array<double, 3>& inertia) {
  hcp_param p = param_of(HCP_P_OBJECT);
  p.hcp_param_u.object.attached = 1;
  p.hcp_param_u.object.mass = mass;
  protocol::to_wire(inertia, p.hcp_param_u.object.inertia);
  impl_->set_param(p, "attach_object");
  const std::lock_guard lock(impl_->state_mutex);
  impl_->passivity.set_object(mass, std::max({inertia[0], inertia[1], inertia[2]}));
}
void Connection::detach_object() {
  impl_->set_param(param_of(HCP_P_OBJECT), "detach_object");
}
void Connection::set_gains(double k_lin, double b_lin, double k_ang, double b_ang) {
  hcp_param p = param_of(HCP_P_GAINS);
  protocol::to_wire(std::array<double, 4>{k_lin, b_lin, k_ang, b_ang}, p.hcp_param_u.gains);
  impl_->set_param(p, "set_gains");
}
void Connection::set_force_limits(double force, double torque) {
  hcp_param p = param_of(HCP_P_FORCE_LIMITS);
  protocol::to_wire(std::array<double, 2>{force, torque}, p.hcp_param_u.force_limits);
  impl_->set_param(p, "set_force_limits");
}
void Connection::set_watchdog(std::chrono::milliseconds timeout) {
  hcp_param p = param_of(HCP_P_WATCHDOG);
  p.hcp_param_u.watchdog_ms = static_cast<std::uint32_t>(
      std::clamp<std::int64_t>(timeout.count(), 0, std::numeric_limits<std::uint32_t>::max()));
  impl_->set_param(p, "set_watchdog");
}
void Connection::set_power(bool on) {
  hcp_param p = param_of(HCP_P_POWER);
  p.hcp_param_u.power_on = on ? 1 : 0;
  impl_->set_param(p, "set_power");
}
void Connection::emergency_stop() {
  impl_->set_param(param_of(HCP_P_EMERGENCY_STOP), "emergency_stop");
}
void Connection::reset_emergency_stop() {
  impl_->set_param(param_of(HCP_P_EMERGENCY_RESET), "reset_emergency_stop");
}

bool Connection::send_object_state(const Pose7& pose, const Vector6& twist) noexcept {
  // Not a rotation: refused in both frame forms (packing would have normalised it silently).
  const double norm_sq =
      pose[3] * pose[3] + pose[4] * pose[4] + pose[5] * pose[5] + pose[6] * pose[6];
  if (!(std::abs(norm_sq - 1.0) <= protocol::kMaxQuaternionError)) {
    return false;
  }
  const std::int64_t now = monotonic_ns();
  if ((impl_->features & HCP_FEATURE_TIMING) != 0) {
    return impl_->send_timed_object(pose, twist, now);
  }
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_OBJECT, impl_->token, impl_->next_control_sequence(), now);
  protocol::to_wire(pose, f.body.hcp_body_u.object.pose);
  protocol::to_wire(twist, f.body.hcp_body_u.object.twist);
  return impl_->send_control(f);
}

bool Connection::send_wrench(const Vector6& wrench) noexcept {
  const std::int64_t now = monotonic_ns();
  hcp_frame f =
      protocol::make_frame(HCP_CONTROL_WRENCH, impl_->token, impl_->next_control_sequence(), now);
  protocol::to_wire(wrench, f.body.hcp_body_u.wrench.wrench);
  return impl_->send_control(f);
}

StateSnapshot Connection::snapshot() const noexcept {
  const std::lock_guard lock(impl_->state_mutex);
  return impl_->latest;
}

bool Connection::wait_for_answer(std::uint64_t after_cycle, std::chrono::nanoseconds timeout,
                                 StateSnapshot& out) const noexcept {
  std::unique_lock lock(impl_->state_mutex);
  const bool got = impl_->answer_cv.wait_for(
      lock, timeout, [&] { return impl_->latest.valid && impl_->latest.cycle > after_cycle; });
  out = impl_->latest;
  return got;
}

LinkStatistics Connection::statistics() const noexcept {
  const std::lock_guard lock(impl_->state_mutex);
  LinkStatistics st =
      impl_->monitor.statistics(impl_->control_sent.load(std::memory_order_relaxed));
  const hcp_coupling_report& r = impl_->report;
  st.link_delay_us = r.link_delay_s * 1e6;
  st.link_jitter_us = r.link_jitter_s * 1e6;
  st.link_loss = r.link_loss;
  st.loop_delay_us = r.loop_delay_s * 1e6;
  st.sample_age_us = r.sample_age_s * 1e6;
  protocol::from_wire(r.gains, st.coupling_gains);
  st.channel_energy_in = impl_->passivity.energy_in();
  st.channel_energy_out = impl_->passivity.energy_out();
  st.controller_energy_in = r.energy_in;
  st.passivity_active_steps = impl_->passivity.active_steps();
  return st;
}

bool Connection::is_open() const noexcept {
  return impl_->open.load();
}

void Connection::start_loop(std::function<void(const StateSnapshot&)> on_cycle) {
  const std::lock_guard lock(impl_->loop_mutex);
  impl_->on_cycle = std::move(on_cycle);
}

void Connection::stop_loop() {
  const std::lock_guard lock(impl_->loop_mutex);  // returns once a running callback finished
  impl_->on_cycle = nullptr;
}

std::uint32_t Connection::features() const noexcept {
  return impl_->features;
}
std::uint32_t Connection::watchdog_ms() const noexcept {
  return impl_->watchdog.load();
}
std::int64_t Connection::controller_period_ns() const noexcept {
  return impl_->period_ns;
}
std::uint32_t Connection::controller_version() const noexcept {
  return impl_->controller_version;
}

}  // namespace hapticctrl::client
