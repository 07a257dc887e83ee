#include "hapticctrl/rt_core/core_config.hpp"

#include <charconv>
#include <stdexcept>

namespace hapticctrl::rt_core {
namespace {

template <typename T>
T parse_number(const std::string& option, const std::string& text, T min, T max) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) {
    throw std::invalid_argument(option + ": '" + text + "' is not a number");
  }
  if (!(value >= min && value <= max)) {  // written so that NaN is out of range too
    throw std::invalid_argument(option + ": " + text + " is out of range [" + std::to_string(min) +
                                ", " + std::to_string(max) + "]");
  }
  return value;
}

}  // namespace

std::string core_usage() {
  return R"(usage: hapticctrl-core [options]
  --instance NAME          instance name (default "default"); its socket is NAME.sock in
                           $HAPTICCTRL_RUNTIME_DIR, else /run/hapticctrl (root), else
                           $XDG_RUNTIME_DIR/hapticctrl or /tmp/hapticctrl-UID
  --group NAME             group whose members may attach (socket mode 0660; default: the
                           core's group)
  --model FILE             arm model file (default: the shipped Virtuose 6D class model)
  --period-us N            cycle period, 100..10000 µs (default 1000)
  --duration S             stop after S seconds (default: run until stopped)
  --rt enforce|warn|ignore real-time policy (default warn)
  --priority N             CLOCK SCHED_FIFO priority 3..98 (SERVO N-1, degraded N-2; default 80)
  --cpu N|-1|auto          pin CLOCK and SERVO to CPU N (auto: last CPU; -1: no pinning)
  --json                   print the final statistics as JSON on stdout
  --histogram FILE         write the wake-up latency histogram (cyclictest -h format)
  --blackbox-dir DIR       where the black box is written on fail-safe (default /tmp)
  --allow-fault-injection  accept overrun injection requests through ctrl
  --inject-overrun C:K     make SERVO overrun for K cycles from cycle C (implies the above)
  --miss-window N          cycles in the miss-rate window (default 1000)
  --trip-miss-ppm N        fail-safe when the window miss rate exceeds N ppm (default 0: report)
  --trip-bucket N          fail-safe when the leaky-bucket score exceeds N (default 0: report)
  --sim-substep-us N       simulator's longest integration sub-step, 10..1000 µs (default 125:
                           0.28 % energy drift in 10 s); longer steps cost less CPU, for
                           slow or instrumented builds, and are less accurate
  --benchmark-mode         simulated arm only: a tripped miss rule (5 consecutive misses,
                           chronic misses) is counted as a would-be fail-safe and the core
                           runs on (a stall pauses the simulated arm); for measurements on
                           machines that stall, never for an arm that moves
  --help                   this text
)";
}

CoreConfig parse_core_args(const std::vector<std::string>& args) {
  CoreConfig c;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& opt = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) {
        throw std::invalid_argument(opt + " needs a value");
      }
      return args[++i];
    };
    if (opt == "--help" || opt == "-h") {
      c.show_help = true;
    } else if (opt == "--instance") {
      c.instance = value();
    } else if (opt == "--group") {
      c.group = value();
    } else if (opt == "--model") {
      c.model_path = value();
    } else if (opt == "--period-us") {
      c.period = parse_number<TimeNs>(opt, value(), 100, 10'000) * kNsPerUs;
    } else if (opt == "--duration") {
      c.duration = static_cast<TimeNs>(parse_number<double>(opt, value(), 0.0, 1e7) * 1e9);
    } else if (opt == "--rt") {
      c.rt_policy = parse_rt_policy(value());
    } else if (opt == "--priority") {
      c.priority = parse_number<int>(opt, value(), 3, 98);
    } else if (opt == "--cpu") {
      const std::string& v = value();
      c.cpu = v == "auto" ? -2 : parse_number<int>(opt, v, -1, 1023);
    } else if (opt == "--json") {
      c.json = true;
    } else if (opt == "--histogram") {
      c.histogram_path = value();
    } else if (opt == "--blackbox-dir") {
      c.blackbox_dir = value();
    } else if (opt == "--allow-fault-injection") {
      c.allow_fault_injection = true;
    } else if (opt == "--inject-overrun") {
      const std::string& v = value();
      const auto colon = v.find(':');
      if (colon == std::string::npos) {
        throw std::invalid_argument("--inject-overrun wants CYCLE:K, got '" + v + "'");
      }
      c.inject_at_cycle = parse_number<std::uint64_t>(opt, v.substr(0, colon), 1, 1ULL << 40);
      c.inject_cycles = parse_number<std::uint32_t>(opt, v.substr(colon + 1), 1, 1000);
      c.allow_fault_injection = true;
    } else if (opt == "--miss-window") {
      c.chronic.window_cycles =
          parse_number<std::uint32_t>(opt, value(), 1, DeadlineMonitor::kMaxWindow);
    } else if (opt == "--trip-miss-ppm") {
      c.chronic.trip_window_ppm = parse_number<std::uint32_t>(opt, value(), 0, 1'000'000);
    } else if (opt == "--sim-substep-us") {
      c.sim_substep = parse_number<TimeNs>(opt, value(), 10, 1000) * kNsPerUs;
    } else if (opt == "--benchmark-mode") {
      c.benchmark_mode = true;
    } else if (opt == "--trip-bucket") {
      c.chronic.trip_bucket = parse_number<std::uint32_t>(opt, value(), 0, 1U << 30);
    } else {
      throw std::invalid_argument("unknown option '" + opt + "' (see --help)");
    }
  }
  return c;
}

}  // namespace hapticctrl::rt_core
