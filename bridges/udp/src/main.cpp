// hapticctrl-udp: the UDP/XDR bridge between one client and a running hapticctrl-core.
//
// Threads: this one receives datagrams, runs the session and its watchdog, and publishes the
// link counters; an answer thread, started per controller attachment, blocks on VP publishes
// and sends one ANSWER per controller cycle. Exit: 0 on signal or --duration, 64 usage, 1 error.
#include <pthread.h>
#include <sched.h>
#include <sys/random.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/program/private_directory.hpp"
#include "hapticctrl/shm/core_watch.hpp"
#include "hapticctrl/shm/names.hpp"
#include "hapticctrl/shm/rendezvous.hpp"
#include "hapticctrl/shm/segment.hpp"
#include "hapticctrl/udp_bridge/bridge_config.hpp"
#include "hapticctrl/udp_bridge/session.hpp"

namespace {

using hapticctrl::MonotonicClock;
using hapticctrl::TimePoint;
using hapticctrl::protocol::Endpoint;
using hapticctrl::protocol::FrameBuffer;
using hapticctrl::protocol::Received;
using hapticctrl::protocol::UdpSocket;
using hapticctrl::udp_bridge::BridgeConfig;
using hapticctrl::udp_bridge::Session;

/// HELLOs answered from all sources together, in multiples of the per-source rate.
constexpr double kTotalHellos = 5.0;
namespace shm = hapticctrl::shm;

std::atomic<bool> g_stop{false};

void on_signal(int /*sig*/) {
  g_stop.store(true);
}

std::uint64_t random_token() {
  std::uint64_t token = 0;
  while (getrandom(&token, sizeof token, 0) != static_cast<ssize_t>(sizeof token)) {
  }
  return token;
}

/// Sends one frame and counts it as sent or failed. Returns whether it went out.
bool send_counted(UdpSocket& socket, Session& session, std::span<const std::uint8_t> frame,
                  const Endpoint& to) {
  const bool sent = socket.send_to(frame, to);
  (sent ? session.counters().frames_out : session.counters().send_failures)
      .fetch_add(1, std::memory_order_relaxed);
  return sent;
}

/// The loop every mode shares: one datagram (or 2 ms), its reply and the watchdog, then
/// `keep_serving(now)`, until it returns false or the bridge is told to stop. (2 ms bounds how
/// late the loss of the core is told to the client; idle, it costs 500 wake-ups a second.)
template <typename KeepServing>
void serve(UdpSocket& socket, Session& session, TimePoint end, KeepServing keep_serving) {
  FrameBuffer in{};
  FrameBuffer reply{};
  while (!g_stop.load()) {
    Endpoint from;
    const Received r = socket.receive(in, from, std::chrono::milliseconds(2));
    const TimePoint now = MonotonicClock::now();
    if (r.status == Received::Status::kDatagram) {
      const std::size_t n = session.on_datagram({in.data(), r.size}, from, now, reply);
      if (n != 0) {
        send_counted(socket, session, {reply.data(), n}, from);
      }
    } else if (r.status == Received::Status::kOversized) {
      session.on_oversized();
    }
    session.check_watchdog(now);
    if (now >= end) {
      g_stop.store(true);
    }
    if (!keep_serving(now)) {
      return;
    }
  }
}

void send_answer(UdpSocket& socket, Session& session, const shm::VpPayload& sample) {
  FrameBuffer out{};
  Endpoint to;
  const std::size_t n = session.answer(sample, MonotonicClock::now(), out, to);
  if (n != 0 && send_counted(socket, session, {out.data(), n}, to)) {
    session.counters().answers_sent.fetch_add(1, std::memory_order_relaxed);
  }
}

/// One ANSWER per controller cycle, until `answering` clears or the core is gone. The end of the
/// core gets a last ANSWER saying so (state stopped, its reason or "core lost"), then sets
/// `core_lost`.
void answer_cycles(const shm::Segment& segment, UdpSocket& socket, Session& session,
                   const std::atomic<bool>& answering, std::atomic<bool>& core_lost,
                   std::atomic<std::uint32_t>& end_reason) {
  const auto& vp = segment.region<shm::RegionId::kVp>();
  shm::CoreWatch watch(segment);
  shm::VpPayload last;
  while (answering.load(std::memory_order_relaxed)) {
    const shm::CoreWatch::Wake wake = watch.wait();
    if (wake == shm::CoreWatch::Wake::kCoreGone) {
      last.core_state = static_cast<std::uint32_t>(shm::CoreState::kStopped);
      last.stop_reason = watch.stop_reason();
      last.state_word &= ~(shm::state_bits::kPowered | shm::state_bits::kCoupled);
      send_answer(socket, session, last);
      std::fprintf(stderr,
                   "hapticctrl-udp: controller '%s' gone after cycle %llu (%s; noticed %.1f ms "
                   "after its last heartbeat)\n",
                   segment.instance().c_str(), static_cast<unsigned long long>(watch.last_cycle()),
                   shm::stop_reason_name(watch.stop_reason()),
                   hapticctrl::to_seconds(watch.heartbeat_age_at_loss()) * 1e3);
      end_reason.store(watch.stop_reason());
      core_lost.store(true);
      return;
    }
    if (wake == shm::CoreWatch::Wake::kCycle && vp.read(last).ok()) {
      send_answer(socket, session, last);
    }
  }
}

/// Black boxes of one instance kept in the state directory, the core's and a lost core's alike
/// (the core's --blackbox-keep default).
constexpr std::size_t kBlackBoxesKept = 20;

/// A core that was lost (killed, crashed) wrote no black box: its last cycles are still in the
/// segment's blackbox region, which this bridge maps, and it writes them out (J4).
void keep_lost_black_box(const shm::Segment& segment, const std::string& state_dir) {
  try {
    const hapticctrl::program::PrivateDirectory directory(
        state_dir.empty() ? shm::creator_runtime_directory() : state_dir);
    const std::vector<shm::CycleRecord> records =
        shm::read_cycle_records(segment.region<shm::RegionId::kBlackBox>());
    const std::string path =
        directory.add_to_series("hapticctrl-blackbox-" + segment.instance() + ".",
                                std::to_string(segment.header().creator_pid) + ".lost", ".csv",
                                shm::cycle_records_csv(records), kBlackBoxesKept);
    std::fprintf(stderr, "hapticctrl-udp: the lost controller's last %zu cycles: black box %s\n",
                 records.size(), path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapticctrl-udp: could not keep the lost controller's black box: %s\n",
                 e.what());
  }
}

/// Serves one controller until it goes away (or the bridge stops). Returns the reason it went
/// (shm::StopReason; 0 while it runs on).
std::uint32_t run_attached(shm::Segment& segment, UdpSocket& socket, Session& session,
                           TimePoint end) {
  hapticctrl::udp_bridge::ControllerPorts ports{
      &segment.writable<shm::RegionId::kVpr>(), &segment.ctrl_writer(),
      hapticctrl::Duration(segment.header().period_ns), &segment.header().heartbeat_cycle};
  auto& stats = segment.writable<shm::RegionId::kLinkStats>();
  session.set_controller(&ports, MonotonicClock::now());

  std::atomic<bool> answering{true};
  std::atomic<bool> core_lost{false};
  std::atomic<std::uint32_t> end_reason{0};
  std::thread answers(
      [&] { answer_cycles(segment, socket, session, answering, core_lost, end_reason); });

  TimePoint next_stats{};
  serve(socket, session, end, [&](TimePoint now) {
    if (now >= next_stats) {
      next_stats = now + std::chrono::milliseconds(100);
      shm::LinkStatsPayload s;
      session.fill_stats(s);
      stats.publish_quietly(s, hapticctrl::to_ns(now));
    }
    return !core_lost.load();
  });
  // Tell the client why its session ends (the core then ramps the coupling out).
  FrameBuffer notice{};
  Endpoint to;
  const bool lost = end_reason.load() == static_cast<std::uint32_t>(shm::StopReason::kCoreLost);
  const char* why = g_stop.load() ? "the bridge is shutting down"
                    : lost        ? "the controller was lost (killed or crashed)"
                                  : "the controller stopped";
  const std::size_t n = session.close(MonotonicClock::now(), why, notice, to);
  if (n != 0) {
    socket.send_to({notice.data(), n}, to);
  }
  session.set_controller(nullptr, MonotonicClock::now());
  shm::LinkStatsPayload s;
  session.fill_stats(s);
  stats.publish_quietly(s, hapticctrl::to_ns(MonotonicClock::now()));
  answering.store(false);
  answers.join();
  if (!g_stop.load()) {
    std::fprintf(stderr, "hapticctrl-udp: waiting for controller '%s'\n",
                 segment.instance().c_str());
  }
  return end_reason.load();
}

void print_json(const Session& session) {
  shm::LinkStatsPayload s;
  session.fill_stats(s);
  std::printf(
      "{\"frames_in\":%llu,\"frames_out\":%llu,\"answers_sent\":%llu,\"control_accepted\":%llu,"
      "\"params_applied\":%llu,\"param_duplicates\":%llu,\"params_rejected\":%llu,"
      "\"sessions_opened\":%llu,\"sessions_closed\":%llu,\"watchdog_expiries\":%llu,"
      "\"refused_busy\":%llu,\"refused_version\":%llu,\"send_failures\":%llu,\"dropped\":{",
      static_cast<unsigned long long>(s.frames_in), static_cast<unsigned long long>(s.frames_out),
      static_cast<unsigned long long>(session.counters().answers_sent.load()),
      static_cast<unsigned long long>(s.control_accepted),
      static_cast<unsigned long long>(s.params_applied),
      static_cast<unsigned long long>(s.param_duplicates),
      static_cast<unsigned long long>(s.params_rejected),
      static_cast<unsigned long long>(s.sessions_opened),
      static_cast<unsigned long long>(s.sessions_closed),
      static_cast<unsigned long long>(s.watchdog_expiries),
      static_cast<unsigned long long>(s.refused_busy),
      static_cast<unsigned long long>(s.refused_version),
      static_cast<unsigned long long>(s.send_failures));
  for (std::size_t i = 0; i < shm::kLinkDropCount; ++i) {
    std::printf("%s\"%s\":%llu", i == 0 ? "" : ",", shm::kLinkDropNames[i],
                static_cast<unsigned long long>(s.dropped[i]));
  }
  std::printf("}}\n");
}

/// SCHED_FIFO for this thread and the threads it starts later (they inherit it). Optional: says
/// once when refused and goes on at normal priority.
void set_priority(int priority) {
  if (priority == 0) {
    return;
  }
  sched_param param{};
  param.sched_priority = priority;
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (rc != 0) {
    std::fprintf(stderr, "hapticctrl-udp: SCHED_FIFO %d refused (%s); running at normal priority\n",
                 priority, std::strerror(rc));
  }
}

int run(const BridgeConfig& config) {
  set_priority(config.priority);
  UdpSocket socket(Endpoint::resolve(config.bind_address, config.port));
  std::printf("hapticctrl-udp: listening on %s for instance '%s'\n",
              socket.local_endpoint().to_string().c_str(), config.instance.c_str());
  std::fflush(stdout);
  Session session({config.watchdog_ms,
                   config.max_watchdog_ms,
                   hapticctrl::udp_bridge::ClientAllowList(config.allowed_clients),
                   {config.hello_rate, config.hello_rate, kTotalHellos * config.hello_rate,
                    kTotalHellos * config.hello_rate / 2.0}},
                  random_token);
  const TimePoint end = hapticctrl::end_after(config.duration_s);
  bool said_waiting = false;
  while (!g_stop.load()) {
    std::optional<shm::Segment> segment = shm::Segment::try_attach(
        config.instance,
        shm::AttachOptions{{shm::RegionId::kVpr, shm::RegionId::kLinkStats}, /*ctrl_writer=*/true});
    if (segment) {
      said_waiting = false;
      if (run_attached(*segment, socket, session, end) ==
          static_cast<std::uint32_t>(shm::StopReason::kCoreLost)) {
        keep_lost_black_box(*segment, config.state_dir);
      }
      continue;
    }
    if (!said_waiting) {
      std::fprintf(stderr, "hapticctrl-udp: no controller for instance '%s' yet; waiting\n",
                   config.instance.c_str());
      said_waiting = true;
    }
    // Serve (refusing HELLOs) for 100 ms, then try to attach again.
    const TimePoint retry_at = MonotonicClock::now() + std::chrono::milliseconds(100);
    serve(socket, session, end, [retry_at](TimePoint now) { return now < retry_at; });
  }
  if (config.json) {
    print_json(session);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<BridgeConfig>(
      "hapticctrl-udp", argc, argv,
      [](const std::vector<std::string>& args, BridgeConfig& c) {
        c = BridgeConfig::parse(args);
        return !c.help;
      },
      &BridgeConfig::usage,
      [](const BridgeConfig& c) {
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        return run(c);
      });
}
