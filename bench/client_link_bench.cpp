// System benchmark of the client link, against a raw UDP ping-pong measured in the same run.
//
//  1. Baseline: a raw UDP ping-pong on loopback (90-byte datagrams, an echo thread).
//  2. Round trip through the client library, hapticctrl-udp and hapticctrl-core: the client
//     answers each controller answer with a control frame (the loop every physics engine
//     runs) and measures until the answer that echoes that frame. Its floor is one controller
//     period (the frame waits for the next cycle); the report gives both ratios.
//  3. The answer stream over --seconds: rate, loss, late frames, inter-arrival percentiles and
//     jitter, against the seed requirement (>= 1 sample per 3 ms, < 1 in 10 lost).
//
// usage: hapticctrl-bench-link --port P [--seconds S] [--pings N] [--json] [--samples PREFIX]
// (bench/client_link.sh and scripts/bench.sh start the core and the bridge, idle and under
// stress-ng.) --samples writes every round trip (µs, one per line) to PREFIX.client_rtt and
// PREFIX.udp_rtt, for distributions and CDF plots.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/protocol/udp_socket.hpp"

namespace {

using namespace std::chrono_literals;
namespace hc = hapticctrl::client;
namespace proto = hapticctrl::protocol;

struct Percentiles {
  double p50 = 0, p99 = 0, p999 = 0, max = 0;
  std::size_t n = 0;
};

Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  p.n = v.size();
  if (v.empty()) {
    return p;
  }
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) {
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
  };
  p.p50 = at(0.5);
  p.p99 = at(0.99);
  p.p999 = at(0.999);
  p.max = v.back();
  return p;
}

/// Raw UDP ping-pong on loopback: the floor of any request/answer over this kernel's stack.
std::vector<double> raw_udp_pingpong(int pings) {
  proto::UdpSocket echo(proto::Endpoint::resolve("127.0.0.1", 0));
  proto::UdpSocket client(proto::Endpoint::resolve("127.0.0.1", 0));
  const proto::Endpoint echo_at = echo.local_endpoint();
  std::atomic<bool> running{true};
  std::thread server([&] {
    std::array<std::uint8_t, 512> buf{};
    while (running.load()) {
      proto::Endpoint from;
      const proto::Received r = echo.receive(buf, from, 20ms);
      if (r.status == proto::Received::Status::kDatagram) {
        echo.send_to({buf.data(), r.size}, from);
      }
    }
  });
  std::vector<double> rtt;
  rtt.reserve(static_cast<std::size_t>(pings));
  std::array<std::uint8_t, 90> ping{};
  std::array<std::uint8_t, 512> pong{};
  for (int i = 0; i < pings; ++i) {
    const hapticctrl::TimePoint t0 = hapticctrl::MonotonicClock::now();
    client.send_to(ping, echo_at);
    proto::Endpoint from;
    if (client.receive(pong, from, 100ms).status == proto::Received::Status::kDatagram) {
      rtt.push_back(hapticctrl::to_seconds(hapticctrl::MonotonicClock::now() - t0) * 1e6);
    }
  }
  running.store(false);
  server.join();
  return rtt;
}

struct StreamResult {
  std::vector<double> rtt_us;
  std::vector<double> interarrival_us;
  hc::LinkStatistics stats;
  double seconds = 0;
  std::int64_t period_ns = 0;
  bool controller_stopped = false;
  std::uint32_t stop_reason = 0;
  std::size_t gaps_over_3ms = 0;
};

/// The answer-synchronous loop: each answer is answered with a control frame.
StreamResult client_loop(std::uint16_t port, double seconds) {
  hc::Connection link({"127.0.0.1", port});
  link.set_command_type(hc::CommandType::kImpedance);
  StreamResult r;
  r.period_ns = link.controller_period_ns();
  const auto expected = static_cast<std::size_t>(seconds * 1e9 / static_cast<double>(r.period_ns));
  r.rtt_us.reserve(expected + 16);
  r.interarrival_us.reserve(expected + 16);
  hc::StateSnapshot s;
  link.wait_for_answer(0, 1s, s);
  std::uint64_t rtt_samples = link.statistics().rtt_samples;
  std::int64_t last_arrival = 0;
  const hapticctrl::TimePoint t0 = hapticctrl::MonotonicClock::now();
  const hapticctrl::TimePoint end = t0 + hapticctrl::from_seconds(seconds);
  while (hapticctrl::MonotonicClock::now() < end) {
    if (!link.wait_for_answer(s.cycle, 100ms, s)) {
      continue;
    }
    if (s.core_state != 1) {  // fail-safe or stop: the stream ends here, and the report says so
      r.controller_stopped = true;
      r.stop_reason = s.stop_reason;
      break;
    }
    if (last_arrival != 0) {
      r.interarrival_us.push_back(static_cast<double>(s.received_ns - last_arrival) / 1e3);
    }
    last_arrival = s.received_ns;
    const hc::LinkStatistics st = link.statistics();
    if (st.rtt_samples != rtt_samples) {
      rtt_samples = st.rtt_samples;
      r.rtt_us.push_back(st.rtt_last_us);
    }
    link.send_wrench({});
  }
  r.seconds = hapticctrl::to_seconds(hapticctrl::MonotonicClock::now() - t0);
  r.stats = link.statistics();
  r.gaps_over_3ms = static_cast<std::size_t>(std::count_if(
      r.interarrival_us.begin(), r.interarrival_us.end(), [](double g) { return g > 3000.0; }));
  return r;
}

void write_samples(const std::string& path, const std::vector<double>& values) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) {
    throw std::runtime_error("cannot write " + path);
  }
  for (const double v : values) {
    std::fprintf(out, "%.1f\n", v);
  }
  std::fclose(out);
}

void print_row(const char* name, const Percentiles& p) {
  std::printf("  %-34s n=%-7zu p50 %8.1f  p99 %8.1f  p99.9 %8.1f  max %8.1f us\n", name, p.n, p.p50,
              p.p99, p.p999, p.max);
}

}  // namespace

int main(int argc, char** argv) {
  std::uint16_t port = 0;
  double seconds = 10.0;
  int pings = 20000;
  bool json = false;
  std::string samples;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--port" && i + 1 < argc) {
      port = static_cast<std::uint16_t>(std::stoi(argv[++i]));
    } else if (a == "--seconds" && i + 1 < argc) {
      seconds = std::stod(argv[++i]);
    } else if (a == "--pings" && i + 1 < argc) {
      pings = std::stoi(argv[++i]);
    } else if (a == "--json") {
      json = true;
    } else if (a == "--samples" && i + 1 < argc) {
      samples = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: %s --port P [--seconds S] [--pings N] [--json] [--samples PREFIX]\n",
                   argv[0]);
      return 64;
    }
  }
  if (port == 0) {
    std::fprintf(stderr, "--port: the hapticctrl-udp port is required\n");
    return 64;
  }
  try {
    const std::vector<double> raw_samples = raw_udp_pingpong(pings);
    const Percentiles raw = percentiles(raw_samples);
    const StreamResult r = client_loop(port, seconds);
    if (!samples.empty()) {
      write_samples(samples + ".udp_rtt", raw_samples);
      write_samples(samples + ".client_rtt", r.rtt_us);
    }
    const Percentiles rtt = percentiles(r.rtt_us);
    const Percentiles gap = percentiles(r.interarrival_us);
    const double period_us = static_cast<double>(r.period_ns) / 1e3;
    const double expected = r.seconds * 1e6 / period_us;
    const double rate_hz = static_cast<double>(r.stats.answers_received) / r.seconds;
    const double received = static_cast<double>(r.stats.answers_received);
    const double loss = static_cast<double>(r.stats.answers_lost) /
                        std::max(1.0, received + static_cast<double>(r.stats.answers_lost));
    const double uplink_loss = 1.0 - static_cast<double>(r.stats.control_received_by_controller) /
                                         std::max(1.0, static_cast<double>(r.stats.control_sent));
    if (json) {
      std::printf(
          "{\"period_us\":%.1f,\"seconds\":%.2f,\"raw_udp_rtt_p50_us\":%.1f,"
          "\"raw_udp_rtt_p99_us\":%.1f,\"raw_udp_rtt_p999_us\":%.1f,\"raw_udp_rtt_max_us\":%.1f,"
          "\"client_rtt_p50_us\":%.1f,\"client_rtt_p99_us\":%.1f,\"client_rtt_p999_us\":%.1f,"
          "\"client_rtt_max_us\":%.1f,\"answers\":%.0f,\"expected\":%.0f,\"lost\":%llu,"
          "\"late\":%llu,\"loss_ratio\":%.6f,\"uplink_loss_ratio\":%.6f,"
          "\"gap_p50_us\":%.1f,\"gap_p99_us\":%.1f,\"gap_p999_us\":%.1f,\"gap_max_us\":%.1f,"
          "\"jitter_us\":%.1f,\"library_gap_max_us\":%.1f,\"gaps_over_3ms\":%zu,"
          "\"controller_stopped\":%s}\n",
          period_us, r.seconds, raw.p50, raw.p99, raw.p999, raw.max, rtt.p50, rtt.p99, rtt.p999,
          rtt.max, received, expected, static_cast<unsigned long long>(r.stats.answers_lost),
          static_cast<unsigned long long>(r.stats.answers_late), loss, uplink_loss, gap.p50,
          gap.p99, gap.p999, gap.max, r.stats.jitter_us, r.stats.interarrival_max_us,
          r.gaps_over_3ms, r.controller_stopped ? "true" : "false");
      return 0;
    }
    std::printf("client link, controller period %.0f us, %.1f s (loopback)\n", period_us,
                r.seconds);
    print_row("raw UDP ping-pong (baseline)", raw);
    print_row("client round trip via bridge+core", rtt);
    std::printf("  ratio client/raw p50 %.1fx; client p50 / period %.2f (floor: 1 period)\n",
                rtt.p50 / std::max(raw.p50, 1e-9), rtt.p50 / period_us);
    print_row("answer inter-arrival (application)", gap);
    std::printf("  receive thread: inter-arrival mean %.1f us, max %.1f us\n",
                r.stats.interarrival_mean_us, r.stats.interarrival_max_us);
    std::printf(
        "  answers %.0f of %.0f expected, lost %llu (%.4f %%), late %llu, "
        "RFC 3550 jitter %.1f us, uplink loss %.4f %%\n",
        received, expected, static_cast<unsigned long long>(r.stats.answers_lost), 100.0 * loss,
        static_cast<unsigned long long>(r.stats.answers_late), r.stats.jitter_us,
        100.0 * uplink_loss);
    std::printf("  gaps over 3 ms: %zu of %zu; mean rate %.1f Hz\n", r.gaps_over_3ms,
                r.interarrival_us.size(), rate_hz);
    std::printf("  seed requirement (>= 1 sample / 3 ms on average, < 1 in 10 lost): %s\n",
                rate_hz >= 1000.0 / 3.0 && loss < 0.1 ? "met" : "NOT met");
    if (r.controller_stopped) {
      std::printf(
          "  the controller left the cycle after %.1f s (stop reason %u): figures up to "
          "then\n",
          r.seconds, r.stop_reason);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapticctrl-bench-link: %s\n", e.what());
    return 1;
  }
}
