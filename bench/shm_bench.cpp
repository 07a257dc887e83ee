// shm/ micro-benchmarks: seqlock publish/read of a VP-sized payload, and cross-process wake-up
// (publish -> blocked reader wakes, as the UDP bridge waits on VP) against a pipe and a UDP
// loopback ping-pong measured in the same run.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <benchmark/benchmark.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <new>
#include <stdexcept>

#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"
#include "support/ratio_reporter.hpp"

namespace {

using hapticctrl::shm::SeqlockCell;
using hapticctrl::shm::VpPayload;
using hapticctrl::shm::WaitStatus;
using namespace std::chrono_literals;

void BM_SeqlockPublishQuietly(benchmark::State& state) {
  SeqlockCell<VpPayload> cell;
  VpPayload vp;
  std::int64_t n = 0;
  for (auto _ : state) {
    vp.cycle = static_cast<std::uint64_t>(++n);
    cell.publish_quietly(vp, n);
  }
}
BENCHMARK(BM_SeqlockPublishQuietly);

void BM_SeqlockPublishWithWake(benchmark::State& state) {
  SeqlockCell<VpPayload> cell;
  VpPayload vp;
  std::int64_t n = 0;
  for (auto _ : state) {
    vp.cycle = static_cast<std::uint64_t>(++n);
    cell.publish(vp, n);  // includes the FUTEX_WAKE syscall (no waiter)
  }
}
BENCHMARK(BM_SeqlockPublishWithWake);

void BM_SeqlockRead(benchmark::State& state) {
  SeqlockCell<VpPayload> cell;
  cell.publish_quietly(VpPayload{}, 1);
  VpPayload out;
  for (auto _ : state) {
    benchmark::DoNotOptimize(cell.read(out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SeqlockRead);

void BM_StructCopyBaseline(benchmark::State& state) {
  VpPayload in;
  VpPayload out;
  for (auto _ : state) {
    benchmark::DoNotOptimize(&in);
    out = in;
    benchmark::DoNotOptimize(&out);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_StructCopyBaseline);

/// Shared between the benchmark process and its echo child.
struct PingPong {
  SeqlockCell<VpPayload> ping;
  SeqlockCell<VpPayload> pong;
  std::atomic<bool> stop{false};
};

/// A forked echo process; killed and reaped on destruction.
class Echo {
 public:
  template <typename Body>
  explicit Echo(Body body) : pid_(fork()) {
    if (pid_ == 0) {
      body();
      _exit(0);
    }
  }
  Echo(const Echo&) = delete;
  Echo& operator=(const Echo&) = delete;
  ~Echo() {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }

 private:
  pid_t pid_;
};

void BM_WakeRoundTripFutex(benchmark::State& state) {
  void* memory =
      mmap(nullptr, sizeof(PingPong), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  auto* pp = new (memory) PingPong();
  std::atomic<std::uint32_t>* ready = &pp->ping.raw_sequence_word();
  const std::uint32_t first_seen = ready->load();
  {
    Echo echo([pp, first_seen] {
      std::uint32_t seen = first_seen;
      VpPayload vp;
      while (!pp->stop.load()) {
        if (pp->ping.wait_for_publish(seen, 1s) != WaitStatus::kPublished) {
          continue;
        }
        seen = pp->ping.sequence_word();
        (void)pp->ping.read(vp);
        pp->pong.publish(vp, 0);
      }
    });
    VpPayload vp;
    for (auto _ : state) {
      const std::uint32_t seen = pp->pong.sequence_word();
      pp->ping.publish(vp, 0);
      if (pp->pong.wait_for_publish(seen, 1s) != WaitStatus::kPublished) {
        state.SkipWithError("echo process did not answer");
        break;
      }
    }
    pp->stop = true;
    pp->ping.publish(vp, 0);
  }
  munmap(memory, sizeof(PingPong));
}
BENCHMARK(BM_WakeRoundTripFutex)->UseRealTime()->MinTime(1.0);

void BM_WakeRoundTripPipe(benchmark::State& state) {
  int to_child[2];
  int to_parent[2];
  if (pipe(to_child) != 0 || pipe(to_parent) != 0) {
    state.SkipWithError("pipe failed");
    return;
  }
  {
    Echo echo([&] {
      std::array<char, sizeof(VpPayload)> buffer{};
      while (read(to_child[0], buffer.data(), buffer.size()) > 0) {
        if (write(to_parent[1], buffer.data(), buffer.size()) < 0) {
          break;
        }
      }
    });
    std::array<char, sizeof(VpPayload)> buffer{};
    for (auto _ : state) {
      if (write(to_child[1], buffer.data(), buffer.size()) < 0 ||
          read(to_parent[0], buffer.data(), buffer.size()) <= 0) {
        state.SkipWithError("pipe echo failed");
        break;
      }
    }
  }
  for (int fd : {to_child[0], to_child[1], to_parent[0], to_parent[1]}) {
    close(fd);
  }
}
BENCHMARK(BM_WakeRoundTripPipe)->UseRealTime()->MinTime(1.0);

int bound_udp_socket(sockaddr_in& address) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  address = sockaddr_in{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    throw std::runtime_error("udp socket setup failed");
  }
  return fd;
}

void BM_WakeRoundTripUdpLoopback(benchmark::State& state) {
  sockaddr_in parent_address{};
  sockaddr_in child_address{};
  const int parent = bound_udp_socket(parent_address);
  const int child = bound_udp_socket(child_address);
  {
    Echo echo([&] {
      std::array<char, sizeof(VpPayload)> buffer{};
      for (;;) {
        const ssize_t n = recv(child, buffer.data(), buffer.size(), 0);
        if (n <= 0) {
          break;
        }
        sendto(child, buffer.data(), static_cast<std::size_t>(n), 0,
               reinterpret_cast<const sockaddr*>(&parent_address), sizeof(parent_address));
      }
    });
    std::array<char, sizeof(VpPayload)> buffer{};
    for (auto _ : state) {
      if (sendto(parent, buffer.data(), buffer.size(), 0,
                 reinterpret_cast<const sockaddr*>(&child_address), sizeof(child_address)) < 0 ||
          recv(parent, buffer.data(), buffer.size(), 0) <= 0) {
        state.SkipWithError("udp echo failed");
        break;
      }
    }
  }
  close(parent);
  close(child);
}
BENCHMARK(BM_WakeRoundTripUdpLoopback)->UseRealTime()->MinTime(1.0);

}  // namespace

int main(int argc, char** argv) {
  const std::string futex = "BM_WakeRoundTripFutex/min_time:1.000/real_time";
  return hapticctrl::bench::run_with_ratios(
      argc, argv,
      {{"BM_SeqlockPublishQuietly", "BM_StructCopyBaseline"},
       {"BM_SeqlockRead", "BM_StructCopyBaseline"},
       {"BM_SeqlockPublishWithWake", "BM_SeqlockPublishQuietly"},
       {futex, "BM_WakeRoundTripPipe/min_time:1.000/real_time"},
       {futex, "BM_WakeRoundTripUdpLoopback/min_time:1.000/real_time"}},
      [](const hapticctrl::bench::RatioReporter&) {});
}
