// The VirtuoseAPI-compatible C API over hapticctrl::client::Connection.
#include "hapticctrl/virtuose_api.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <unordered_set>
#include <utility>

#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/monotonic_clock.hpp"

namespace {

using hapticctrl::client::ClientError;
using hapticctrl::client::CommandType;
using hapticctrl::client::Connection;
using hapticctrl::client::ErrorCode;
using hapticctrl::client::Pose7;
using hapticctrl::client::StateSnapshot;
using hapticctrl::client::Vector6;
using hapticctrl::protocol::monotonic_ns;

constexpr std::size_t kDetailBytes = 256;

struct ErrorState {
  int code = VIRT_E_NO_ERROR;
  std::array<char, kDetailBytes> detail{};

  int set(int c, const char* text) noexcept {
    code = c;
    std::snprintf(detail.data(), detail.size(), "%s", text);
    return -1;
  }
};

thread_local ErrorState t_open_error;  // errors of virtOpen and of calls with a NULL context

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

template <std::size_t N>
std::array<double, N> to_doubles(const float* v) noexcept {
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = static_cast<double>(v[i]);
  }
  return out;
}

template <std::size_t N>
void to_floats(const std::array<double, N>& v, float* out) noexcept {
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = static_cast<float>(v[i]);
  }
}

}  // namespace

struct VirtContextS {
  std::unique_ptr<Connection> connection;
  ErrorState error;

  /// The parameters as the controller acknowledged them, for the getters (a getter right after a
  /// successful setter returns the new value). Guarded by pending_mutex.
  struct Settings {
    float time_step = 0.0F;  ///< 0 until set: the controller's answers pace the application
    float force_factor = 1.0F;
    float speed_factor = 1.0F;
    VirtIndexingType indexing = INDEXING_ALL;
    std::array<float, 7> base_frame{0, 0, 0, 0, 0, 0, 1};
    std::array<float, 7> observation_frame{0, 0, 0, 0, 0, 0, 1};
    VirtCommandType command_type = COMMAND_TYPE_NONE;
  };

  std::mutex pending_mutex;  // the application's thread and the loop's callback both set these
  Settings settings;
  CommandType command_type = CommandType::kNone;
  Pose7 object_pose{0, 0, 0, 0, 0, 0, 1};
  Vector6 object_speed{};
  Vector6 wrench{};
  Vector6 added_wrench{};
  bool pose_pending = false;
  bool wrench_pending = false;

  void (*periodic)(VirtContext, void*) = nullptr;
  void* periodic_arg = nullptr;
  unsigned decimation = 1;
  unsigned answers_since_call = 0;
  std::atomic<bool> loop_running{false};

  /// Runs `call`, mapping a ClientError to -1 with its code and text.
  template <typename Call>
  int guarded(Call&& call) noexcept {
    try {
      call();
      return 0;
    } catch (const ClientError& e) {
      return error.set(code_of(e.code()), e.what());
    } catch (const std::bad_alloc&) {
      return error.set(VIRT_E_OUT_OF_MEMORY, "out of memory");
    } catch (const std::exception& e) {
      return error.set(VIRT_E_COMMUNICATION_FAILURE, e.what());
    }
  }

  /// Sends the pending control frame (at most one per call). Caller holds pending_mutex.
  bool flush_locked() noexcept {
    bool ok = true;
    if (command_type == CommandType::kVirtmech && pose_pending) {
      ok = connection->send_object_state(object_pose, object_speed);
    } else if (command_type == CommandType::kImpedance && wrench_pending) {
      Vector6 total{};
      for (std::size_t i = 0; i < 6; ++i) {
        total[i] = wrench[i] + added_wrench[i];
      }
      ok = connection->send_wrench(total);
      added_wrench = {};
    }
    pose_pending = false;
    wrench_pending = false;
    return ok;
  }

  void on_answer() noexcept {
    if (periodic == nullptr || ++answers_since_call < decimation) {
      return;
    }
    answers_since_call = 0;
    periodic(this, periodic_arg);
    const std::lock_guard lock(pending_mutex);
    flush_locked();
  }
};

namespace {

/// Every context virtOpen returned and virtClose has not closed: a closed, foreign or NULL
/// handle is recognised as such (it was used after free).
struct LiveContexts {
  std::mutex mutex;
  std::unordered_set<const VirtContextS*> contexts;
};

LiveContexts& live() noexcept {
  static LiveContexts registry;
  return registry;
}

bool registered(VirtContext vc) noexcept {
  LiveContexts& l = live();
  const std::lock_guard lock(l.mutex);
  return vc != nullptr && l.contexts.count(vc) != 0;
}

/// The context's error state, or the thread's for a NULL or unknown context.
int fail(VirtContext vc, int code, const char* text) noexcept {
  return registered(vc) ? vc->error.set(code, text) : t_open_error.set(code, text);
}

/// A live context; otherwise VIRT_E_INVALID_CONTEXT in the thread's error state.
bool valid(VirtContext vc) noexcept {
  if (!registered(vc)) {
    t_open_error.set(
        VIRT_E_INVALID_CONTEXT,
        vc == nullptr ? "NULL context" : "invalid context: closed, or not returned by virtOpen");
    return false;
  }
  return true;
}

/// A live context and a non-NULL argument (else VIRT_E_INCORRECT_VALUE saying `what`).
bool ready(VirtContext vc, const void* argument, const char* what) noexcept {
  if (!valid(vc)) {
    return false;
  }
  if (argument == nullptr) {
    vc->error.set(VIRT_E_INCORRECT_VALUE, what);
    return false;
  }
  return true;
}

/// Runs a parameter setter's call; on success records what the controller acknowledged.
template <typename Call, typename Record>
int set_and_record(VirtContext vc, Call&& call, Record&& record) noexcept {
  const int rc = vc->guarded(std::forward<Call>(call));
  if (rc == 0) {
    const std::lock_guard lock(vc->pending_mutex);
    record(vc->settings);
  }
  return rc;
}

/// Copies one acknowledged setting out, for a getter.
template <typename Read>
int get_setting(VirtContext vc, const void* out, const char* what, Read&& read) noexcept {
  if (!ready(vc, out, what)) {
    return -1;
  }
  const std::lock_guard lock(vc->pending_mutex);
  read(vc->settings);
  return 0;
}

/// How long virtOpen waits for the controller's first answer, and a setter for its effect.
constexpr auto kFirstAnswerTimeout = std::chrono::seconds(2);
constexpr auto kEffectTimeout = std::chrono::milliseconds(500);

StateSnapshot state_of(VirtContext vc) noexcept {
  return vc->connection->snapshot();
}

}  // namespace

extern "C" {
// NOLINTBEGIN(readability-identifier-naming): VirtuoseAPI's names

VirtContext virtOpen(const char* name) {
  if (name == nullptr) {
    fail(nullptr, VIRT_E_WRONG_FORMAT, "virtOpen: NULL address");
    return nullptr;
  }
  try {
    auto vc = std::make_unique<VirtContextS>();
    vc->connection = std::make_unique<Connection>(hapticctrl::client::Address::parse(name));
    // As Haption's: returns once the controller's first answer is here, so that the getters
    // report the arm, never a default pose (they did, in 9 opens of 10).
    StateSnapshot first;
    if (!vc->connection->wait_for_answer(0, kFirstAnswerTimeout, first)) {
      fail(nullptr, VIRT_E_TIME_OUT,
           "virtOpen: the session opened, but no answer from the controller came within 2 s");
      return nullptr;
    }
    t_open_error = ErrorState{};
    LiveContexts& l = live();
    const std::lock_guard lock(l.mutex);
    l.contexts.insert(vc.get());
    return vc.release();
  } catch (const ClientError& e) {
    fail(nullptr, e.code() == ErrorCode::kInvalidArgument ? VIRT_E_WRONG_FORMAT : code_of(e.code()),
         e.what());
  } catch (const std::exception& e) {
    fail(nullptr, VIRT_E_COMMUNICATION_FAILURE, e.what());
  }
  return nullptr;
}

int virtClose(VirtContext vc) {
  if (!valid(vc)) {
    return -1;
  }
  virtStopLoop(vc);
  const int rc = vc->guarded([&] { vc->connection->close(); });
  {
    LiveContexts& l = live();
    const std::lock_guard lock(l.mutex);
    l.contexts.erase(vc);
  }
  delete vc;  // NOLINT(cppcoreguidelines-owning-memory): the C API hands out raw handles
  return rc;
}

int virtSetTimeStep(VirtContext vc, float step) {
  if (!valid(vc)) {
    return -1;
  }
  return set_and_record(
      vc, [&] { vc->connection->set_time_step(static_cast<double>(step)); },
      [&](VirtContextS::Settings& s) { s.time_step = step; });
}

int virtSetIndexingMode(VirtContext vc, VirtIndexingType mode) {
  if (!valid(vc)) {
    return -1;
  }
  return set_and_record(
      vc,
      [&] {
        vc->connection->set_indexing_mode(static_cast<hapticctrl::client::IndexingMode>(mode));
      },
      [&](VirtContextS::Settings& s) { s.indexing = mode; });
}

int virtSetForceFactor(VirtContext vc, float factor) {
  if (!valid(vc)) {
    return -1;
  }
  return set_and_record(
      vc, [&] { vc->connection->set_force_factor(static_cast<double>(factor)); },
      [&](VirtContextS::Settings& s) { s.force_factor = factor; });
}

int virtSetSpeedFactor(VirtContext vc, float factor) {
  if (!valid(vc)) {
    return -1;
  }
  return set_and_record(
      vc, [&] { vc->connection->set_speed_factor(static_cast<double>(factor)); },
      [&](VirtContextS::Settings& s) { s.speed_factor = factor; });
}

int virtSetBaseFrame(VirtContext vc, float* pos) {
  if (!ready(vc, pos, "virtSetBaseFrame: NULL pose")) {
    return -1;
  }
  return set_and_record(
      vc, [&] { vc->connection->set_base_frame(to_doubles<7>(pos)); },
      [&](VirtContextS::Settings& s) { std::copy_n(pos, 7, s.base_frame.begin()); });
}

int virtSetObservationFrame(VirtContext vc, float* pos) {
  if (!ready(vc, pos, "virtSetObservationFrame: NULL pose")) {
    return -1;
  }
  return set_and_record(
      vc, [&] { vc->connection->set_observation_frame(to_doubles<7>(pos)); },
      [&](VirtContextS::Settings& s) { std::copy_n(pos, 7, s.observation_frame.begin()); });
}

int virtGetTimeStep(VirtContext vc, float* step) {
  return get_setting(vc, step, "virtGetTimeStep: NULL output",
                     [&](const VirtContextS::Settings& s) { *step = s.time_step; });
}

int virtGetIndexingMode(VirtContext vc, VirtIndexingType* mode) {
  return get_setting(vc, mode, "virtGetIndexingMode: NULL output",
                     [&](const VirtContextS::Settings& s) { *mode = s.indexing; });
}

int virtGetForceFactor(VirtContext vc, float* factor) {
  return get_setting(vc, factor, "virtGetForceFactor: NULL output",
                     [&](const VirtContextS::Settings& s) { *factor = s.force_factor; });
}

int virtGetSpeedFactor(VirtContext vc, float* factor) {
  return get_setting(vc, factor, "virtGetSpeedFactor: NULL output",
                     [&](const VirtContextS::Settings& s) { *factor = s.speed_factor; });
}

int virtGetBaseFrame(VirtContext vc, float* pos) {
  return get_setting(vc, pos, "virtGetBaseFrame: NULL output",
                     [&](const VirtContextS::Settings& s) {
                       std::copy(s.base_frame.begin(), s.base_frame.end(), pos);
                     });
}

int virtGetObservationFrame(VirtContext vc, float* pos) {
  return get_setting(vc, pos, "virtGetObservationFrame: NULL output",
                     [&](const VirtContextS::Settings& s) {
                       std::copy(s.observation_frame.begin(), s.observation_frame.end(), pos);
                     });
}

int virtGetCommandType(VirtContext vc, VirtCommandType* type) {
  return get_setting(vc, type, "virtGetCommandType: NULL output",
                     [&](const VirtContextS::Settings& s) { *type = s.command_type; });
}

int virtGetTimeoutValue(VirtContext vc, float* seconds) {
  if (!ready(vc, seconds, "virtGetTimeoutValue: NULL output")) {
    return -1;
  }
  // The watchdog in force: the bridge may have capped what was asked (--max-watchdog-ms).
  *seconds = static_cast<float>(vc->connection->watchdog_ms()) / 1000.0F;
  return 0;
}

int virtGetControlerVersion(VirtContext vc, int* major, int* minor) {
  if (!ready(vc, major, "virtGetControlerVersion: NULL output") ||
      !ready(vc, minor, "virtGetControlerVersion: NULL output")) {
    return -1;
  }
  const std::uint32_t version = vc->connection->controller_version();
  *major = static_cast<int>(hapticctrl::protocol::version_major(version));
  *minor = static_cast<int>(hapticctrl::protocol::version_minor(version));
  return 0;
}

int virtSetCommandType(VirtContext vc, VirtCommandType type) {
  if (!valid(vc)) {
    return -1;
  }
  CommandType t = CommandType::kNone;
  switch (type) {
    case COMMAND_TYPE_NONE:
      break;
    case COMMAND_TYPE_IMPEDANCE:
      t = CommandType::kImpedance;
      break;
    case COMMAND_TYPE_VIRTMECH:
      t = CommandType::kVirtmech;
      break;
    default:
      return fail(vc, VIRT_E_MODE_NOT_SUPPORTED,
                  "virtSetCommandType: hapticctrl's controller has COMMAND_TYPE_NONE, "
                  "COMMAND_TYPE_IMPEDANCE and COMMAND_TYPE_VIRTMECH only");
  }
  const int rc = vc->guarded([&] { vc->connection->set_command_type(t); });
  if (rc == 0) {
    const std::lock_guard lock(vc->pending_mutex);
    vc->command_type = t;
    vc->settings.command_type = type;
  }
  return rc;
}

int virtAttachVO(VirtContext vc, float mass, float* mxmymz) {
  if (!ready(vc, mxmymz, "virtAttachVO: NULL inertia")) {
    return -1;
  }
  return vc->guarded(
      [&] { vc->connection->attach_object(static_cast<double>(mass), to_doubles<3>(mxmymz)); });
}

int virtDetachVO(VirtContext vc) {
  return valid(vc) ? vc->guarded([&] { vc->connection->detach_object(); }) : -1;
}

int virtSetPowerOn(VirtContext vc, int power) {
  if (!valid(vc)) {
    return -1;
  }
  const bool on = power != 0;
  if (vc->guarded([&] { vc->connection->set_power(on); }) != 0) {
    return -1;
  }
  if (vc->loop_running.load()) {
    return 0;  // from the periodic function: the next answers show it (waiting would stall them)
  }
  // The acknowledgement says the bridge passed it on; return once the controller did it (a getter
  // then reports it), or say why not.
  StateSnapshot s = state_of(vc);
  const std::int64_t deadline = monotonic_ns() + std::chrono::nanoseconds(kEffectTimeout).count();
  while (s.powered() != on) {
    if (on && s.emergency_stop()) {
      return fail(vc, VIRT_E_CONTROLLER_REFUSED,
                  "virtSetPowerOn: the emergency stop is latched (reset it first)");
    }
    const std::int64_t left = deadline - monotonic_ns();
    if (left <= 0 || !vc->connection->wait_for_answer(s.cycle, std::chrono::nanoseconds(left), s)) {
      return fail(vc, VIRT_E_TIME_OUT, "virtSetPowerOn: the controller did not switch the power");
    }
  }
  return 0;
}

int virtSetTimeoutValue(VirtContext vc, float seconds) {
  if (!valid(vc)) {
    return -1;
  }
  if (!std::isfinite(seconds)) {
    return fail(vc, VIRT_E_INCORRECT_VALUE, "virtSetTimeoutValue: not a finite number");
  }
  const auto ms = std::chrono::milliseconds(std::lround(static_cast<double>(seconds) * 1000.0));
  return vc->guarded([&] { vc->connection->set_watchdog(ms); });
}

int virtSaturateTorque(VirtContext vc, float force_threshold, float moment_threshold) {
  return valid(vc) ? vc->guarded([&] {
    vc->connection->set_force_limits(static_cast<double>(force_threshold),
                                     static_cast<double>(moment_threshold));
  })
                   : -1;
}

int virtSetPosition(VirtContext vc, float* pos) {
  if (!ready(vc, pos, "virtSetPosition: NULL pose")) {
    return -1;
  }
  const std::lock_guard lock(vc->pending_mutex);
  if (vc->command_type != CommandType::kVirtmech) {
    return fail(vc, VIRT_E_WRONG_MODE, "virtSetPosition: needs COMMAND_TYPE_VIRTMECH");
  }
  vc->object_pose = to_doubles<7>(pos);
  vc->pose_pending = true;
  if (!vc->loop_running.load() && !vc->flush_locked()) {
    return fail(vc, VIRT_E_INCORRECT_VALUE,
                "virtSetPosition: pose or speed out of range, or "
                "the session is closed");
  }
  return 0;
}

int virtSetSpeed(VirtContext vc, float* speed) {
  if (!ready(vc, speed, "virtSetSpeed: NULL speed")) {
    return -1;
  }
  const std::lock_guard lock(vc->pending_mutex);
  vc->object_speed = to_doubles<6>(speed);
  return 0;
}

int virtSetForce(VirtContext vc, float* force) {
  if (!ready(vc, force, "virtSetForce: NULL force")) {
    return -1;
  }
  const std::lock_guard lock(vc->pending_mutex);
  if (vc->command_type != CommandType::kImpedance) {
    return fail(vc, VIRT_E_WRONG_MODE, "virtSetForce: needs COMMAND_TYPE_IMPEDANCE");
  }
  vc->wrench = to_doubles<6>(force);
  vc->wrench_pending = true;
  if (!vc->loop_running.load() && !vc->flush_locked()) {
    return fail(vc, VIRT_E_INCORRECT_VALUE,
                "virtSetForce: force out of range, or the session is closed");
  }
  return 0;
}

int virtAddForce(VirtContext vc, float* force) {
  if (!ready(vc, force, "virtAddForce: NULL force")) {
    return -1;
  }
  const std::lock_guard lock(vc->pending_mutex);
  if (vc->command_type != CommandType::kImpedance) {
    return fail(vc, VIRT_E_WRONG_MODE,
                "virtAddForce: needs COMMAND_TYPE_IMPEDANCE (control frames carry either an "
                "object state or a wrench)");
  }
  const Vector6 f = to_doubles<6>(force);
  for (std::size_t i = 0; i < 6; ++i) {
    vc->added_wrench[i] += f[i];
  }
  vc->wrench_pending = true;
  return 0;
}

int virtGetPosition(VirtContext vc, float* pos) {
  if (!ready(vc, pos, "virtGetPosition: NULL output")) {
    return -1;
  }
  to_floats(state_of(vc).handle_pose, pos);
  return 0;
}

int virtGetSpeed(VirtContext vc, float* speed) {
  if (!ready(vc, speed, "virtGetSpeed: NULL output")) {
    return -1;
  }
  to_floats(state_of(vc).handle_twist, speed);
  return 0;
}

int virtGetForce(VirtContext vc, float* force) {
  if (!ready(vc, force, "virtGetForce: NULL output")) {
    return -1;
  }
  to_floats(state_of(vc).coupling_wrench, force);
  return 0;
}

int virtGetArticularPosition(VirtContext vc, float* pos) {
  if (!ready(vc, pos, "virtGetArticularPosition: NULL output")) {
    return -1;
  }
  to_floats(state_of(vc).joint_position, pos);
  return 0;
}

int virtGetArticularSpeed(VirtContext vc, float* speed) {
  if (!ready(vc, speed, "virtGetArticularSpeed: NULL output")) {
    return -1;
  }
  to_floats(state_of(vc).joint_velocity, speed);
  return 0;
}

int virtGetPowerOn(VirtContext vc, int* power) {
  if (!ready(vc, power, "virtGetPowerOn: NULL output")) {
    return -1;
  }
  *power = state_of(vc).powered() ? 1 : 0;
  return 0;
}

int virtGetEmergencyStop(VirtContext vc, int* emergency_stop) {
  if (!ready(vc, emergency_stop, "virtGetEmergencyStop: NULL output")) {
    return -1;
  }
  // Haption's meaning: 1 while the arm is operational (the emergency stop is not latched and a
  // controller answers), 0 otherwise.
  const StateSnapshot s = state_of(vc);
  *emergency_stop = s.valid && !s.emergency_stop() && vc->connection->is_open() ? 1 : 0;
  return 0;
}

int virtGetTimeLastUpdate(VirtContext vc, unsigned int* time) {
  if (!ready(vc, time, "virtGetTimeLastUpdate: NULL output")) {
    return -1;
  }
  const StateSnapshot s = state_of(vc);
  if (!s.valid) {
    return fail(vc, VIRT_E_TIME_OUT, "virtGetTimeLastUpdate: no answer from the controller yet");
  }
  const std::int64_t us = (monotonic_ns() - s.received_ns) / 1000;
  *time = static_cast<unsigned int>(std::clamp<std::int64_t>(us, 0, 0xFFFFFFFF));
  return 0;
}

int virtSetPeriodicFunction(VirtContext vc, void (*fn)(VirtContext, void*), float* period,
                            void* arg) {
  if (!valid(vc)) {
    return -1;
  }
  if (fn == nullptr || period == nullptr || !std::isfinite(*period) || *period <= 0.0F) {
    return fail(vc, VIRT_E_INCORRECT_VALUE, "virtSetPeriodicFunction: NULL function or bad period");
  }
  if (vc->loop_running.load()) {
    return fail(vc, VIRT_E_WRONG_MODE, "virtSetPeriodicFunction: stop the loop first");
  }
  const double cycle_s = static_cast<double>(vc->connection->controller_period_ns()) / 1e9;
  vc->decimation =
      cycle_s > 0.0
          ? static_cast<unsigned>(std::max(1L, std::lround(static_cast<double>(*period) / cycle_s)))
          : 1U;
  *period = static_cast<float>(static_cast<double>(vc->decimation) *
                               cycle_s);  // the period actually used
  vc->periodic = fn;
  vc->periodic_arg = arg;
  return 0;
}

int virtStartLoop(VirtContext vc) {
  if (!valid(vc)) {
    return -1;
  }
  if (vc->periodic == nullptr) {
    return fail(vc, VIRT_E_WRONG_MODE, "virtStartLoop: call virtSetPeriodicFunction first");
  }
  vc->loop_running.store(true);
  return vc->guarded(
      [&] { vc->connection->start_loop([vc](const StateSnapshot&) { vc->on_answer(); }); });
}

int virtStopLoop(VirtContext vc) {
  if (!valid(vc)) {
    return -1;
  }
  vc->connection->stop_loop();
  vc->loop_running.store(false);
  return 0;
}

int virtGetErrorCode(VirtContext vc) {
  return registered(vc) ? vc->error.code : t_open_error.code;
}

char* virtGetErrorMessage(int code) {
  // Indexed by VirtuoseAPI's codes, 0 to 21; hapticctrl's own from 100.
  static char kTexts[][40] = {// NOLINT(*-avoid-c-arrays): the C API returns char*
                              "no error",
                              "out of memory",
                              "communication failure",
                              "invalid context",
                              "file not found",
                              "wrong format",
                              "time out",
                              "not implemented",
                              "variable not available",
                              "incorrect value",
                              "syntax error",
                              "hardware error",
                              "position discontinuity",
                              "library not found",
                              "periodic function error",
                              "performance counter error",
                              "major/minor version mismatch",
                              "wrong mode",
                              "mode not supported",
                              "call time error",
                              "incompatible version",
                              "incorrect virtual mechanism type",
                              "controller busy",
                              "controller refused",
                              "unknown error"};
  constexpr int kHaptionCodes = 22;
  constexpr int kOwnFirst = VIRT_E_VIRTUOSE_BUSY;
  constexpr int kOwnCount = 2;
  if (code >= 0 && code < kHaptionCodes) {
    return kTexts[code];
  }
  if (code >= kOwnFirst && code < kOwnFirst + kOwnCount) {
    return kTexts[kHaptionCodes + code - kOwnFirst];
  }
  return kTexts[kHaptionCodes + kOwnCount];
}

const char* virtGetErrorDetail(VirtContext vc) {
  return registered(vc) ? vc->error.detail.data() : t_open_error.detail.data();
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
