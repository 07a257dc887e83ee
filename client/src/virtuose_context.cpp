// The registry of live C API contexts, their error states and their control frames.
#include "virtuose_context.hpp"

#include <chrono>
#include <cstring>
#include <unordered_map>

#include "hapticctrl/base/time.hpp"
#include "virtuose_reconnect.hpp"

namespace hapticctrl::client::virtuose {
namespace {

thread_local ErrorState t_thread_error;  // virtOpen's, and calls with an invalid context
thread_local const Context* t_in_periodic = nullptr;  // whose periodic function this thread runs

/// Every context virtOpen returned and virtClose has not closed: a closed, foreign or NULL
/// handle is recognised as such, never dereferenced.
struct Registry {
  std::mutex mutex;
  std::unordered_map<const void*, std::unique_ptr<Context>> contexts;
};

Registry& registry() noexcept {
  static Registry r;
  return r;
}

Context* find(VirtContext vc) noexcept {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  const auto it = r.contexts.find(vc);
  return it == r.contexts.end() ? nullptr : it->second.get();
}

}  // namespace

int ErrorState::set(int c, const char* text) noexcept {
  code = c;
  std::snprintf(detail.data(), detail.size(), "%s", text);
  return -1;
}

int code_of(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::kInvalidArgument:
      return VIRT_E_INCORRECT_VALUE;
    case ErrorCode::kBusy:
      return VIRT_E_VIRTUOSE_BUSY;
    case ErrorCode::kVersion:
      return VIRT_E_INCOMPATIBLE_VERSION;
    case ErrorCode::kTimeout:
      return VIRT_E_TIME_OUT;
    case ErrorCode::kRejected:
      return VIRT_E_CONTROLLER_REFUSED;
    case ErrorCode::kNoController:
    case ErrorCode::kClosed:
    case ErrorCode::kTransport:
      break;
  }
  return VIRT_E_COMMUNICATION_FAILURE;
}

void register_context(std::unique_ptr<Context> context) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  const void* key = context.get();
  r.contexts.emplace(key, std::move(context));
  t_thread_error = ErrorState{};
}

std::unique_ptr<Context> unregister_context(VirtContext vc) noexcept {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  const auto it = r.contexts.find(vc);
  if (it == r.contexts.end()) {
    return nullptr;
  }
  std::unique_ptr<Context> c = std::move(it->second);
  r.contexts.erase(it);
  return c;
}

Context* context_of(VirtContext vc) noexcept {
  Context* c = find(vc);
  if (c == nullptr) {
    t_thread_error.set(
        VIRT_E_INVALID_CONTEXT,
        vc == nullptr ? "NULL context" : "invalid context: closed, or not returned by virtOpen");
  }
  return c;
}

Context* context_of(VirtContext vc, const void* argument, const char* what) noexcept {
  Context* c = context_of(vc);
  if (c != nullptr && argument == nullptr) {
    c->error.set(VIRT_E_INCORRECT_VALUE, what);
    return nullptr;
  }
  return c;
}

ErrorState& error_of(VirtContext vc) noexcept {
  Context* c = find(vc);
  return c != nullptr ? c->error : t_thread_error;
}

int fail(VirtContext vc, int code, const char* text) noexcept {
  return error_of(vc).set(code, text);
}

Context::~Context() {
  if (output != nullptr) {
    std::fclose(output);  // NOLINT(cppcoreguidelines-owning-memory): the C library's handle
  }
}

bool Context::in_periodic_function() const noexcept {
  return t_in_periodic == this;
}

int Context::flush_locked(const char* what) noexcept {
  const std::shared_ptr<Connection> c = link();
  const StateSnapshot s = c->snapshot();
  // Forces off (virtEnableForceFeedback(0), or a shift in an inhibiting mode): no wrench, and an
  // object that goes with the handle, so that the coupling pulls neither.
  const bool forces_off = !force_feedback || indexing.forces_inhibited();
  bool ok = true;
  if (command_type == CommandType::kVirtmech && pose_pending) {
    ok = forces_off ? c->send_object_state(s.handle_pose, s.handle_twist)
                    : c->send_object_state(indexing.to_physical(s.handle_pose, object_pose),
                                           indexing.to_physical(s.handle_pose, object_speed));
  } else if (command_type == CommandType::kImpedance && wrench_pending) {
    Vector6 total{};
    for (std::size_t i = 0; i < 6 && !forces_off; ++i) {
      total[i] = wrench[i] + added_wrench[i];
    }
    ok = c->send_wrench(indexing.to_physical(s.handle_pose, total));
    added_wrench = {};
  } else if (command_type == CommandType::kArticular && joints_pending) {
    ok = c->send_joint_target(joint_position, joint_speed);
  } else if (command_type == CommandType::kArticularImpedance && joints_pending) {
    ok = c->send_joint_torque(forces_off ? Joints6{} : joint_torque);
  }
  pose_pending = false;
  wrench_pending = false;
  joints_pending = false;
  if (ok) {
    return 0;
  }
  return c->is_open() ? error.set(VIRT_E_INCORRECT_VALUE, what) : fail_without_session(s);
}

int Context::fail_without_session(const StateSnapshot& last) noexcept {
  std::array<char, ErrorState::kDetailBytes> text{};
  std::snprintf(text.data(), text.size(),
                last.stopped_in_order()
                    ? "no session: the %s in order (virtClose, then virtOpen for a new one)"
                    : "no session: %s; the library connects to the next controller",
                last.ending());
  return error.set(VIRT_E_COMMUNICATION_FAILURE, text.data());
}

void Context::on_answer(const StateSnapshot& s) noexcept {
  const unsigned flags = debug_flags.load(std::memory_order_relaxed);
  if ((flags & DEBUG_SERVO) != 0U) {
    const std::lock_guard lock(mutex);
    std::fprintf(
        debug_stream(),
        "virtuose servo: cycle %llu state 0x%x handle %.4f %.4f %.4f force %.3f %.3f %.3f\n",
        static_cast<unsigned long long>(s.cycle), s.state_word, s.handle_pose[0], s.handle_pose[1],
        s.handle_pose[2], s.coupling_wrench[0], s.coupling_wrench[1], s.coupling_wrench[2]);
  }
  if (periodic == nullptr || ++answers_since_call < decimation) {
    return;
  }
  answers_since_call = 0;
  const TimePoint start = MonotonicClock::now();
  t_in_periodic = this;
  periodic(this, periodic_arg);
  t_in_periodic = nullptr;
  const Duration took = MonotonicClock::now() - start;
  const Duration period = Duration(link()->controller_period_ns()) * decimation;
  const std::lock_guard lock(mutex);
  flush_locked("the periodic function's command");
  if (period > Duration::zero() && took > period) {
    alarms |= VIRT_ALARM_CALLBACK_OVERRUN;
  }
  if ((flags & DEBUG_LOOP) != 0U) {
    std::fprintf(debug_stream(), "virtuose loop: cycle %llu call %.1f us of a %.1f us period\n",
                 static_cast<unsigned long long>(s.cycle), to_seconds(took) * 1e6,
                 to_seconds(period) * 1e6);
  }
}

}  // namespace hapticctrl::client::virtuose
