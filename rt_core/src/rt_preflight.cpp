// Implements rt_preflight.hpp: real-time preflight: what the machine and our privileges allow,
// tried once at start.
#include "hapticctrl/rt_core/rt_preflight.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/utsname.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace hapticctrl::rt_core {
namespace {

long soft_limit(int resource, long unit) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0) {
    return 0;
  }
  return limit.rlim_cur == RLIM_INFINITY ? -1 : static_cast<long>(limit.rlim_cur) / unit;
}

bool file_contains(const std::string& path, const std::string& needle) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str().find(needle) != std::string::npos;
}

std::string detect_virtualization() {
  const bool vm = file_contains("/proc/cpuinfo", " hypervisor");
  const bool container =
      std::ifstream("/.dockerenv").good() || std::ifstream("/run/.containerenv").good() ||
      file_contains("/proc/1/cgroup", "docker") || file_contains("/proc/1/cgroup", "kubepods");
  if (vm && container) {
    return "vm+container";
  }
  return vm ? "vm" : (container ? "container" : "none");
}

bool probe_fifo(int priority) {
  bool granted = false;
  std::thread probe([&] {
    sched_param param{};
    param.sched_priority = priority;
    granted = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
  });
  probe.join();
  return granted;
}

}  // namespace

RtPolicy parse_rt_policy(const std::string& text) {
  if (text == "enforce") {
    return RtPolicy::kEnforce;
  }
  if (text == "warn") {
    return RtPolicy::kWarn;
  }
  if (text == "ignore") {
    return RtPolicy::kIgnore;
  }
  throw std::invalid_argument("--rt must be enforce, warn or ignore (got '" + text + "')");
}

shm::RtMode RtReport::mode() const noexcept {
  if (!fifo_granted) {
    return shm::RtMode::kNone;
  }
  if (!memory_locked) {
    return shm::RtMode::kFifo;
  }
  return preempt_rt ? shm::RtMode::kFifoLockedRt : shm::RtMode::kFifoLocked;
}

std::string RtReport::summary() const {
  std::ostringstream out;
  out << "real-time: kernel " << kernel << " (" << (preempt_rt ? "PREEMPT_RT" : "not PREEMPT_RT")
      << "), virtualization " << virtualization << ", SCHED_FIFO "
      << (fifo_granted ? "granted" : "NOT granted") << ", memory "
      << (memory_locked ? "locked" : "NOT locked") << ", RLIMIT_RTPRIO " << rtprio_limit
      << ", RLIMIT_MEMLOCK "
      << (memlock_limit_kib < 0 ? std::string("unlimited")
                                : std::to_string(memlock_limit_kib) + " KiB");
  for (const auto& p : problems) {
    out << "\n  - " << p;
  }
  return out.str();
}

RtReport rt_preflight(RtPolicy policy, int fifo_priority) {
  RtReport report;
  utsname name{};
  if (uname(&name) == 0) {
    report.kernel = std::string(name.release) + " " + name.version;
  }
  report.preempt_rt = std::ifstream("/sys/kernel/realtime").good() ||
                      report.kernel.find("PREEMPT_RT") != std::string::npos;
  report.virtualization = detect_virtualization();
  report.rtprio_limit = soft_limit(RLIMIT_RTPRIO, 1);
  report.memlock_limit_kib = soft_limit(RLIMIT_MEMLOCK, 1024);
  report.fifo_granted = probe_fifo(fifo_priority);
#ifdef HAPTICCTRL_SANITIZED
  // A sanitizer's shadow is terabytes of reserved address space: locking it cannot work.
  report.memory_locked = false;
  constexpr const char* kNotLocked = "sanitizer build: memory not locked (shadow memory)";
#else
  report.memory_locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  constexpr const char* kNotLocked =
      "mlockall refused: raise RLIMIT_MEMLOCK; page faults may hit the cycle";
#endif

  if (!report.fifo_granted) {
    report.problems.push_back(
        "SCHED_FIFO priority " + std::to_string(fifo_priority) +
        " refused: run as root or raise RLIMIT_RTPRIO; timing is best effort");
  }
  if (!report.memory_locked) {
    report.problems.push_back(kNotLocked);
  }
  if (!report.preempt_rt) {
    report.problems.push_back("kernel is not PREEMPT_RT: expect millisecond outliers under load");
  }
  if (report.virtualization != "none") {
    report.problems.push_back("running in a " + report.virtualization +
                              ": vCPU scheduling adds latency outside our control");
  }
  if (policy == RtPolicy::kEnforce && (!report.fifo_granted || !report.memory_locked)) {
    throw std::runtime_error("--rt enforce: real-time requirements not met\n" + report.summary());
  }
  return report;
}

}  // namespace hapticctrl::rt_core
