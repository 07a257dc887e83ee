#pragma once
/// @file virtuose_context.hpp
/// What stands behind a VirtContext, and the checks every C API function begins with. Private to
/// the client library (the virtuose_*.cpp files implement the C API over it).
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/virtuose_api.h"
#include "indexing.hpp"

namespace hapticctrl::client::virtuose {

/// How long virtOpen, and the reconnector for each next session, wait for the controller's first
/// answer.
inline constexpr auto kFirstAnswerTimeout = std::chrono::seconds(2);

/// The last error of a context, or of a thread (virtOpen, calls with an invalid context).
struct ErrorState {
  static constexpr std::size_t kDetailBytes = 256;
  int code = VIRT_E_NO_ERROR;
  std::array<char, kDetailBytes> detail{};

  /// Records the error; returns -1, the C API's failure value.
  int set(int c, const char* text) noexcept;
};

/// The VirtuoseAPI code of a client library error.
int code_of(ErrorCode code) noexcept;

/// The virtual object virtAttachVO attached (virtAttachQSVO: no mass).
struct AttachedObject {
  double mass = 0.0;
  std::array<double, 3> inertia{};
};

/// The parameters as the controller acknowledged them: for the getters, and replayed in this
/// order on the next session when the library reconnects (virtuose_reconnect.hpp).
struct Settings {
  float time_step = 0.0F;  ///< 0 until set: the controller's answers pace the application
  float force_factor = 1.0F;
  float speed_factor = 1.0F;
  VirtIndexingType indexing = INDEXING_ALL;
  std::array<float, 7> base_frame{0, 0, 0, 0, 0, 0, 1};
  std::array<float, 7> observation_frame{0, 0, 0, 0, 0, 0, 1};
  VirtCommandType command_type = COMMAND_TYPE_NONE;
  std::optional<std::array<double, 4>> gains;         ///< virtAttachQSVO's, as set_gains takes
  std::optional<AttachedObject> object;               ///< until virtDetachVO
  std::optional<std::array<double, 2>> force_limits;  ///< virtSaturateTorque's
  std::optional<std::chrono::milliseconds> watchdog;  ///< virtSetTimeoutValue's
  std::array<Contact, kMaxContacts> contacts{};       ///< virtSetContacts', as the session took
  std::size_t contact_count = 0;
  bool power = false;  ///< the application's last virtSetPowerOn
};

class Reconnector;

/// One session of the C API.
struct Context {
  /// The session in force. A call takes it once and keeps it for its duration: the reconnector
  /// replaces it when the controller is lost, and the old one lives on until its last user is
  /// done with it. (A mutex, not std::atomic<std::shared_ptr>: libstdc++ 12's lock bit is
  /// invisible to ThreadSanitizer, which reported the hand-over as a race.)
  [[nodiscard]] std::shared_ptr<Connection> link() const noexcept {
    const std::lock_guard lock(link_mutex);
    return connection;
  }
  void set_link(std::shared_ptr<Connection> next) noexcept {
    const std::lock_guard lock(link_mutex);
    connection = std::move(next);
  }
  mutable std::mutex link_mutex;
  std::shared_ptr<Connection> connection;  ///< under link_mutex
  Address address;                         ///< virtOpen's, where the next session is opened
  ErrorState error;

  /// Guards everything below: the application's threads and the loop's callback use it.
  std::mutex mutex;
  Settings settings;
  CommandType command_type = CommandType::kNone;
  Indexing indexing;
  bool force_feedback = true;  ///< virtEnableForceFeedback
  Pose7 object_pose{0, 0, 0, 0, 0, 0, 1};
  Vector6 object_speed{};
  Vector6 wrench{};
  Vector6 added_wrench{};
  Joints6 joint_position{};  ///< virtSetArticularPosition (ARTICULAR)
  Joints6 joint_speed{};     ///< virtSetArticularSpeed (ARTICULAR)
  Joints6 joint_torque{};    ///< virtSetArticularForce (ARTICULAR_IMPEDANCE)
  bool pose_pending = false;
  bool wrench_pending = false;
  bool joints_pending = false;
  std::uint32_t alarms = 0;              ///< VIRT_ALARM_* raised since virtGetAlarm last read them
  std::atomic<unsigned> debug_flags{0};  ///< DEBUG_* (read outside `mutex` too)
  std::FILE* output = nullptr;  ///< virtSetOutputFile's, owned; nullptr: stderr; written to
                                ///< under `mutex` only (virtSetOutputFile may close it)

  VirtPeriodicFunction periodic = nullptr;
  void* periodic_arg = nullptr;
  unsigned decimation = 1;
  unsigned answers_since_call = 0;
  std::atomic<bool> loop_running{false};
  /// Serialises starting and stopping the loop with the reconnector's hand-over, so that the
  /// loop runs on the session in force exactly when the application started it.
  std::mutex loop_control;
  /// Opens the next session when the controller is lost (virtOpen starts it, virtClose stops it
  /// first); declared last, so that it stops before anything it uses goes.
  std::unique_ptr<Reconnector> reconnector;

  Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  Context(Context&&) = delete;
  Context& operator=(Context&&) = delete;
  ~Context();

  /// Runs `call`, mapping an exception to -1 with its code and text.
  template <typename Call>
  int guarded(Call&& call) noexcept {
    try {
      std::forward<Call>(call)();
      return 0;
    } catch (const ClientError& e) {
      return error.set(code_of(e.code()), e.what());
    } catch (const std::bad_alloc&) {
      return error.set(VIRT_E_OUT_OF_MEMORY, "out of memory");
    } catch (const std::exception& e) {
      return error.set(VIRT_E_COMMUNICATION_FAILURE, e.what());
    }
  }

  /// Sends the pending control frame (at most one per call), through the indexing and with the
  /// forces off while inhibited. Caller holds `mutex`. Returns 0, or -1 with the error set
  /// (VIRT_E_COMMUNICATION_FAILURE without a session, else VIRT_E_INCORRECT_VALUE naming `what`).
  int flush_locked(const char* what) noexcept;
  /// Records VIRT_E_COMMUNICATION_FAILURE for a call while no session is open (`last`: the
  /// session's last answer, saying how it ended); returns -1.
  int fail_without_session(const StateSnapshot& last) noexcept;
  /// The loop's callback, after each controller answer.
  void on_answer(const StateSnapshot& s) noexcept;
  /// Whether this thread is inside this context's periodic function (virtStopLoop from there
  /// must not wait for the loop's locks, which the running function holds).
  [[nodiscard]] bool in_periodic_function() const noexcept;
  /// Where debug lines go. Caller holds `mutex`.
  [[nodiscard]] std::FILE* debug_stream() const noexcept {
    return output != nullptr ? output : stderr;
  }
};

/// The loop's callback on any of `context`'s sessions: the periodic function (Context::on_answer).
inline std::function<void(const StateSnapshot&)> periodic_callback(Context* context) {
  return [context](const StateSnapshot& s) { context->on_answer(s); };
}

/// Adds a context virtOpen created to the registry (it owns it from then on).
void register_context(std::unique_ptr<Context> context);
/// Removes a live context from the registry and returns it (to be destroyed).
std::unique_ptr<Context> unregister_context(VirtContext vc) noexcept;

/// The live context `vc` names, or nullptr with VIRT_E_INVALID_CONTEXT in the thread's error.
Context* context_of(VirtContext vc) noexcept;
/// The same, and `argument` non-NULL (else VIRT_E_INCORRECT_VALUE saying `what`).
Context* context_of(VirtContext vc, const void* argument, const char* what) noexcept;
/// The error state of `vc`, or the thread's for a NULL or unknown context.
ErrorState& error_of(VirtContext vc) noexcept;
/// Records an error for `vc` (or the thread); returns -1.
int fail(VirtContext vc, int code, const char* text) noexcept;

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

}  // namespace hapticctrl::client::virtuose
