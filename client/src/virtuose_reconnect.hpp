#pragma once
/// @file virtuose_reconnect.hpp
/// A C API context's way back to the controller (J4): when the session ends other than in
/// order (the controller killed, crashed or failed safe, or the bridge gone silent), a thread
/// opens a session with the next controller at the same address, replays what the application
/// set (Settings, in the order the seeds set them up), and hands the new session to the context
/// and its loop. The controller ramps the coupling in as for any new session. Meanwhile every
/// call that needs the controller fails with VIRT_E_COMMUNICATION_FAILURE. Private to the client
/// library; not for the real-time path (it blocks and allocates).
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "virtuose_context.hpp"

namespace hapticctrl::client::virtuose {

/// Sets the next session `c` up as `s` says (each a blocking, acknowledged call). The power is
/// asked for as the application last asked; a controller that refuses it (an emergency stop, or
/// a restart awaiting its operator, J8) leaves it to the operator and the session is kept.
/// Throws ClientError when the controller refuses anything else or does not answer.
void replay(const Settings& s, CommandType command_type, Connection& c);

class Reconnector {
 public:
  /// Starts watching `context`'s session; the context must outlive this object.
  explicit Reconnector(Context& context);
  /// Stops the watch: within one connection attempt (kAttemptTimeout) and one replay.
  ~Reconnector();
  Reconnector(const Reconnector&) = delete;
  Reconnector& operator=(const Reconnector&) = delete;
  Reconnector(Reconnector&&) = delete;
  Reconnector& operator=(Reconnector&&) = delete;

  /// How long one attempt to open the next session waits for its WELCOME.
  static constexpr std::chrono::milliseconds kAttemptTimeout{500};
  /// How often the session is looked at, and the pause between attempts.
  static constexpr std::chrono::milliseconds kWatchPeriod{20};
  static constexpr std::chrono::milliseconds kRetryPause{200};

 private:
  void run();
  /// The next session, set up; nullptr once stopping.
  std::shared_ptr<Connection> next_session(std::unique_lock<std::mutex>& lock);
  /// Makes `next` the context's session (the loop moves with it) and waits a little for the
  /// calls still using `old` (the caller's is then the last reference).
  void hand_over(const std::shared_ptr<Connection>& old, const std::shared_ptr<Connection>& next);
  /// A line on the context's debug stream (virtSetOutputFile, or stderr).
  void say(const std::string& line);

  Context& context_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::uint64_t sessions_ = 1;
  std::thread thread_;
};

}  // namespace hapticctrl::client::virtuose
