// hapticctrl-bench-peers: the seqlock regions side by side with iceoryx, LCM and UDP (H8), in one
// run, cross-process, on the same payload (a VP sample), the same CPUs and priority. Per
// transport and read mode: the publish -> observed latency (medians of repeated runs), the cost of
// a read and of a publish, the CPU time per 1000 messages at 1 kHz and 10 kHz, and what a writer
// goes through while its reader is stopped and then killed. One JSON document on stdout, which
// bench/report_peers.py turns into the report's table (docs/benchmark.md).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/program/options.hpp"
#include "peers/peer_runner.hpp"
#include "peers/peer_stats.hpp"

namespace hapticctrl::bench {
namespace {

struct PeerBenchConfig {
  std::uint32_t messages = 5000;  ///< per latency run, at 1 kHz
  std::uint32_t repeats = 3;
  double cpu_seconds = 3.0;  ///< per CPU run (1 kHz and 10 kHz)
  std::uint32_t stall_messages = 2500;
  int writer_cpu = -1;
  int reader_cpu = -1;
  int priority = 60;
  std::string only;  ///< one transport by name (empty: all)
  std::string roudi = "iox-roudi";
  bool smoke = false;
};

void declare(program::Options& o, PeerBenchConfig& c) {
  o.number("--messages", c.messages, 100U, 50'000U, "messages per latency run (1 kHz)")
      .number("--repeats", c.repeats, 1U, 20U, "latency runs per case (the median is reported)")
      .number("--cpu-seconds", c.cpu_seconds, 0.1, 60.0, "length of each CPU-time run")
      .number("--stall-messages", c.stall_messages, 100U, 50'000U, "messages of the stall run")
      .number("--writer-cpu", c.writer_cpu, -1, 1023, "the writer's CPU (-1: the last)")
      .number("--reader-cpu", c.reader_cpu, -1, 1023, "the reader's CPU (-1: the first)")
      .number("--priority", c.priority, 0, 98, "SCHED_FIFO priority of both (0: SCHED_OTHER)")
      .text("--only", c.only, "run this transport only (seqlock, iceoryx, lcm, udp, dds)")
      .text("--roudi", c.roudi, "iceoryx's broker to start (its path)")
      .flag("--smoke", c.smoke, "short runs: checks the pipeline, not the machine");
}

/// iceoryx's broker, started for the iceoryx cases and stopped after them.
class Roudi {
 public:
  explicit Roudi(const std::string& binary) {
    log_ = "/tmp/hapticctrl-roudi-" + std::to_string(getpid()) + ".log";
    std::fflush(nullptr);  // the child's freopen would write what stdout still holds
    pid_ = fork();
    if (pid_ == 0) {
      std::freopen(log_.c_str(), "w", stdout);
      std::freopen(log_.c_str(), "a", stderr);
      execlp(binary.c_str(), binary.c_str(), nullptr);
      _exit(127);
    }
    for (int i = 0; i < 500 && !ready(); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!ready()) {
      error_ = binary + " did not become ready (Debian package iceoryx; log: " + log_ + ")";
    }
  }
  Roudi(const Roudi&) = delete;
  Roudi& operator=(const Roudi&) = delete;
  ~Roudi() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    std::remove(log_.c_str());
  }
  [[nodiscard]] const std::string& error() const { return error_; }

 private:
  bool ready() const {
    std::ifstream in(log_);
    std::string line;
    while (std::getline(in, line)) {
      if (line.find("RouDi is ready for clients") != std::string::npos) {
        return true;
      }
    }
    return false;
  }
  pid_t pid_ = -1;
  std::string log_;
  std::string error_;
};

void print_case(PeerTransport& t, ReadMode mode, const PeerBenchConfig& c, const Placement& p,
                bool first) {
  std::vector<RunResult> latency;
  latency.reserve(c.repeats);
  for (std::uint32_t i = 0; i < c.repeats; ++i) {
    latency.push_back(run_peers(t, {.mode = mode, .messages = c.messages}, p));
  }
  const auto at = [&](double hz) {
    return run_peers(
        t,
        {.mode = mode, .rate_hz = hz, .messages = static_cast<std::uint32_t>(hz * c.cpu_seconds)},
        p);
  };
  const RunResult cpu_1k = at(1000.0);
  const RunResult cpu_10k = at(10000.0);
  const RunResult stall =
      run_peers(t, {.mode = mode, .messages = c.stall_messages, .stall_reader = true}, p);
  std::printf("%s", first ? "" : ",\n");
  print_case_json(stdout, t.name(), mode_name(mode), c.messages, latency, cpu_1k, cpu_10k, stall);
  std::fflush(stdout);
}

int run(const PeerBenchConfig& config) {
  PeerBenchConfig c = config;
  if (c.smoke) {
    c.messages = 300;
    c.repeats = 1;
    c.cpu_seconds = 0.2;
    c.stall_messages = 500;
  }
  const int cpus = static_cast<int>(std::thread::hardware_concurrency());
  const Placement placement{.writer_cpu = c.writer_cpu >= 0 ? c.writer_cpu : cpus - 1,
                            .reader_cpu = c.reader_cpu >= 0 ? c.reader_cpu : 0,
                            .priority = c.priority};
  std::vector<std::unique_ptr<PeerTransport>> transports;
  transports.push_back(make_seqlock_transport());
  transports.push_back(make_iceoryx_transport());
  transports.push_back(make_lcm_transport());
  transports.push_back(make_udp_transport());
  transports.push_back(make_dds_transport());
  std::printf(
      "{\"clock_read_ns\":%lld,\"writer_cpu\":%d,\"reader_cpu\":%d,\"priority\":%d,"
      "\"messages\":%u,\"repeats\":%u,\"cpu_seconds\":%g,\"stall_messages\":%u,\n"
      "\"cases\":[\n",
      static_cast<long long>(clock_read_ns()), placement.writer_cpu, placement.reader_cpu,
      placement.priority, c.messages, c.repeats, c.cpu_seconds, c.stall_messages);
  bool first = true;
  for (const auto& t : transports) {
    if (!c.only.empty() && t->name() != c.only) {
      continue;
    }
    std::unique_ptr<Roudi> roudi;
    if (t->name() == "iceoryx") {
      roudi = std::make_unique<Roudi>(c.roudi);
      if (!roudi->error().empty()) {
        std::printf("%s{\"transport\":\"iceoryx\",\"error\":\"%s\"}", first ? "" : ",\n",
                    roudi->error().c_str());
        first = false;
        continue;
      }
    }
    for (const ReadMode mode : t->modes()) {
      std::fprintf(stderr, "peers: %s (%s)\n", t->name().c_str(), mode_name(mode));
      print_case(*t, mode, c, placement, first);
      first = false;
    }
  }
  std::printf("\n]}\n");
  return 0;
}

}  // namespace
}  // namespace hapticctrl::bench

int main(int argc, char** argv) {
  using hapticctrl::bench::PeerBenchConfig;
  constexpr const char* kProgram = "hapticctrl-bench-peers";
  constexpr const char* kAbout =
      "The seqlock regions against iceoryx, LCM, UDP and DDS, in one run.";
  return hapticctrl::program::main_skeleton<PeerBenchConfig>(
      kProgram, argc, argv,
      [&](const std::vector<std::string>& args, PeerBenchConfig& c) {
        return hapticctrl::program::parse_into(c, args, kProgram, kAbout,
                                               hapticctrl::bench::declare);
      },
      [&] {
        return hapticctrl::program::help_of<PeerBenchConfig>(kProgram, kAbout,
                                                             hapticctrl::bench::declare);
      },
      hapticctrl::bench::run);
}
