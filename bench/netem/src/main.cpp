// hapticctrl-netem: a UDP relay that impairs the link between a client and hapticctrl-udp
// (delay, jitter, loss, loss bursts, blackouts), for tests and the coupling benchmark. This
// kernel has no netem qdisc (../shared/PITFALLS.md), so the impairment is done in user space.
//
//   client --> [--listen] hapticctrl-netem --> [--to] hapticctrl-udp
//   client <-- (same socket)                <-- (its own socket)
//
// The client talks to the relay's address instead of the bridge's. Datagrams from the bridge go
// back to the client that last sent one. SIGUSR1 switches a blackout on and off (both
// directions); SIGINT/SIGTERM end it, and --json prints its counters. Loopback only unless
// --allow-remote: a test tool never sends traffic off this machine by accident.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <queue>
#include <stdexcept>
#include <string>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/netem/impairment.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/program/options.hpp"

namespace {

using hapticctrl::Duration;
using hapticctrl::MonotonicClock;
using hapticctrl::TimePoint;
using hapticctrl::netem::Impairment;
using hapticctrl::netem::LinkModel;
using hapticctrl::netem::Verdict;

std::atomic<bool> g_stop{false};
std::atomic<int> g_toggles{0};

void on_stop(int /*signal*/) {
  g_stop.store(true);
}
void on_toggle(int /*signal*/) {
  g_toggles.fetch_add(1);
}

struct Options {
  std::string listen = "127.0.0.1:0";
  std::string to;
  LinkModel link;
  std::uint64_t seed = 1;
  double duration_s = 0.0;
  bool json = false;
  bool allow_remote = false;
};

constexpr const char* kProgram = "hapticctrl-netem";
constexpr const char* kDescription =
    "A UDP relay that impairs the link between a client and hapticctrl-udp (each direction "
    "alike). Clients send to --listen instead of the bridge. SIGUSR1 switches a blackout on and "
    "off; SIGINT/SIGTERM end it.";

/// A time in milliseconds within [0, 10 s].
std::function<void(const std::string&)> milliseconds_into(const std::string& option,
                                                          Duration& target) {
  return [option, &target](const std::string& v) {
    target =
        hapticctrl::from_seconds(hapticctrl::program::number_in(option, v, 0.0, 10000.0) / 1e3);
  };
}

/// Every option, once: parse and --help both read these declarations.
void declare(hapticctrl::program::Options& o, Options& c) {
  o.text("--listen", c.listen,
         "HOST:PORT where clients send (default 127.0.0.1:0: a free port, printed)");
  o.text("--to", c.to, "HOST:PORT of the bridge (hapticctrl-udp) to relay to (required)");
  o.custom("--delay-ms", "MS", milliseconds_into("--delay-ms", c.link.delay),
           "one-way delay added in each direction, ms (default 0) [0..10000]");
  o.custom("--jitter-ms", "MS", milliseconds_into("--jitter-ms", c.link.jitter),
           "each datagram's delay varies uniformly within +-MS (default 0) [0..10000]");
  o.number("--loss", c.link.loss, 0.0, 1.0,
           "fraction of datagrams lost in each direction (default 0)");
  o.number("--burst", c.link.burst, 1.0, 1e6, "mean loss-burst length in datagrams (default 1)");
  o.flag("--reorder", c.link.reorder, "let jitter reorder datagrams (default: keep their order)");
  o.custom(
      "--blackout", "AT:DUR",
      [&c](const std::string& v) { c.link.blackouts.push_back(LinkModel::parse_blackout(v)); },
      "drop everything from AT s for DUR s (repeatable)", /*repeat=*/true);
  o.number<std::uint64_t>("--seed", c.seed, 0, 9'000'000'000'000'000ULL, "random seed (default 1)");
  o.number("--duration", c.duration_s, 0.0, 1e6, "exit after S seconds (default: run on)");
  o.flag("--allow-remote", c.allow_remote, "allow addresses outside 127.0.0.0/8");
  o.flag("--json", c.json, "print the counters as one JSON line at exit");
}

/// The options; false when --help was given.
bool parse(const std::vector<std::string>& args, Options& o) {
  if (!hapticctrl::program::parse_into(o, args, kProgram, kDescription, declare)) {
    return false;
  }
  if (o.to.empty()) {
    throw std::invalid_argument("--to HOST:PORT is required");
  }
  o.link.validate();
  return true;
}

sockaddr_in endpoint(const std::string& text, bool allow_remote) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) {
    throw std::invalid_argument("'" + text + "': expected HOST:PORT (IPv4)");
  }
  sockaddr_in a{};
  a.sin_family = AF_INET;
  const std::string host =
      text.substr(0, colon) == "localhost" ? "127.0.0.1" : text.substr(0, colon);
  if (inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1) {
    throw std::invalid_argument("'" + text + "': not an IPv4 address");
  }
  a.sin_port =
      htons(hapticctrl::program::number_in<std::uint16_t>(text, text.substr(colon + 1), 0, 65535));
  if (!allow_remote && (ntohl(a.sin_addr.s_addr) >> 24U) != 127U) {
    throw std::invalid_argument("'" + text + "' is not on loopback (--allow-remote to allow)");
  }
  return a;
}

/// Where the relay's own socket towards the bridge is bound: loopback for a bridge on loopback,
/// otherwise any address, so that the kernel sends from the interface that reaches the bridge
/// (a relay on a client's host in front of a remote bridge: tests/multihost).
sockaddr_in towards(const sockaddr_in& bridge) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr =
      (ntohl(bridge.sin_addr.s_addr) >> 24U) == 127U ? htonl(INADDR_LOOPBACK) : htonl(INADDR_ANY);
  return a;
}

int bound_socket(const sockaddr_in& at) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0 || bind(fd, reinterpret_cast<const sockaddr*>(&at), sizeof at) != 0) {
    throw std::runtime_error(std::string("cannot bind the relay's socket: ") +
                             std::strerror(errno));
  }
  return fd;
}

struct Counters {
  std::uint64_t received = 0, delivered = 0, lost = 0, blackout = 0, overflow = 0;
};

struct Pending {
  TimePoint at;
  std::uint64_t order = 0;
  std::size_t direction = 0;  ///< 0: client -> bridge, 1: bridge -> client
  std::uint16_t size = 0;
  std::array<std::uint8_t, 1500> bytes{};
  bool operator>(const Pending& other) const {
    return at != other.at ? at > other.at : order > other.order;
  }
};

/// Datagrams waiting for their delivery time; bounded (an overflow is counted, not queued).
constexpr std::size_t kMaxPending = 65536;

class Relay {
 public:
  explicit Relay(const Options& o)
      : options_(o),
        front_(bound_socket(endpoint(o.listen, o.allow_remote))),
        back_(bound_socket(towards(endpoint(o.to, o.allow_remote)))),
        bridge_(endpoint(o.to, o.allow_remote)),
        links_{Impairment(o.link, o.seed), Impairment(o.link, o.seed * 7919 + 1)} {}
  ~Relay() {
    close(front_);
    close(back_);
  }
  Relay(const Relay&) = delete;
  Relay& operator=(const Relay&) = delete;

  [[nodiscard]] std::uint16_t port() const {
    sockaddr_in a{};
    socklen_t n = sizeof a;
    getsockname(front_, reinterpret_cast<sockaddr*>(&a), &n);
    return ntohs(a.sin_port);
  }

  void run() {
    const TimePoint start = MonotonicClock::now();
    const TimePoint end = hapticctrl::end_after(options_.duration_s);
    int toggles_seen = 0;
    while (!g_stop.load() && MonotonicClock::now() < end) {
      const int toggles = g_toggles.load();
      if (toggles != toggles_seen) {
        toggles_seen = toggles;
        for (Impairment& l : links_) {
          l.set_manual_blackout(toggles % 2 == 1);
        }
        std::fprintf(stderr, "hapticctrl-netem: blackout %s\n", toggles % 2 == 1 ? "on" : "off");
      }
      wait_for_traffic();
      const TimePoint now = MonotonicClock::now();
      receive(front_, 0, now, now - start);
      receive(back_, 1, now, now - start);
      deliver_due(MonotonicClock::now());
    }
  }

  void print_json() const {
    const auto side = [](const Counters& c) {
      char text[200];
      std::snprintf(
          text, sizeof text,
          "{\"received\":%llu,\"delivered\":%llu,\"lost\":%llu,\"blackout\":%llu,"
          "\"overflow\":%llu}",
          static_cast<unsigned long long>(c.received), static_cast<unsigned long long>(c.delivered),
          static_cast<unsigned long long>(c.lost), static_cast<unsigned long long>(c.blackout),
          static_cast<unsigned long long>(c.overflow));
      return std::string(text);
    };
    std::printf("{\"to_bridge\":%s,\"to_client\":%s}\n", side(counters_[0]).c_str(),
                side(counters_[1]).c_str());
  }

 private:
  void wait_for_traffic() {
    std::array<pollfd, 2> fds{pollfd{front_, POLLIN, 0}, pollfd{back_, POLLIN, 0}};
    Duration wait = std::chrono::milliseconds(10);  // wake every 10 ms: signals, the end
    if (!queue_.empty()) {
      wait = std::clamp(queue_.top().at - MonotonicClock::now(), Duration::zero(), wait);
    }
    const timespec ts{0, static_cast<long>(wait.count())};  // < 1 s
    ppoll(fds.data(), fds.size(), &ts, nullptr);
  }

  void receive(int fd, std::size_t direction, TimePoint now, Duration since_start) {
    for (;;) {
      Pending p;
      sockaddr_in from{};
      socklen_t n = sizeof from;
      const ssize_t got =
          recvfrom(fd, p.bytes.data(), p.bytes.size(), 0, reinterpret_cast<sockaddr*>(&from), &n);
      if (got < 0) {
        return;  // EAGAIN: nothing more now
      }
      if (direction == 0) {
        client_ = from;
        have_client_ = true;
      } else if (from.sin_addr.s_addr != bridge_.sin_addr.s_addr ||
                 from.sin_port != bridge_.sin_port) {
        continue;  // only the bridge answers on this socket
      }
      Counters& c = counters_[direction];
      ++c.received;
      const Verdict v = links_[direction].on_datagram(now, since_start);
      if (v.fate == Verdict::Fate::kLost) {
        ++c.lost;
        continue;
      }
      if (v.fate == Verdict::Fate::kBlackout) {
        ++c.blackout;
        continue;
      }
      if (queue_.size() >= kMaxPending) {
        ++c.overflow;
        continue;
      }
      p.at = v.deliver_at;
      p.order = ++order_;
      p.direction = direction;
      p.size = static_cast<std::uint16_t>(got);
      queue_.push(p);
    }
  }

  void deliver_due(TimePoint now) {
    while (!queue_.empty() && queue_.top().at <= now) {
      const Pending& p = queue_.top();
      const bool to_bridge = p.direction == 0;
      if (to_bridge || have_client_) {
        const sockaddr_in& to = to_bridge ? bridge_ : client_;
        if (sendto(to_bridge ? back_ : front_, p.bytes.data(), p.size, 0,
                   reinterpret_cast<const sockaddr*>(&to), sizeof to) >= 0) {
          ++counters_[p.direction].delivered;
        }
      }
      queue_.pop();
    }
  }

  Options options_;
  int front_;
  int back_;
  sockaddr_in bridge_;
  sockaddr_in client_{};
  bool have_client_ = false;
  std::array<Impairment, 2> links_;
  std::priority_queue<Pending, std::vector<Pending>, std::greater<>> queue_;
  std::uint64_t order_ = 0;
  std::array<Counters, 2> counters_{};
};

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<Options>(
      kProgram, argc, argv, parse,
      [] { return hapticctrl::program::help_of<Options>(kProgram, kDescription, declare); },
      [](const Options& options) {
        Relay relay(options);
        std::signal(SIGINT, on_stop);
        std::signal(SIGTERM, on_stop);
        std::signal(SIGUSR1, on_toggle);
        std::printf("hapticctrl-netem: listening on 127.0.0.1:%u\n", relay.port());
        std::fflush(stdout);
        relay.run();
        if (options.json) {
          relay.print_json();
        }
        return 0;
      });
}
