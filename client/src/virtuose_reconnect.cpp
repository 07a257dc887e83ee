// The C API's reconnection: the watch over a context's session, the next session's set-up, and
// the hand-over (virtuose_reconnect.hpp).
#include "virtuose_reconnect.hpp"

#include <chrono>
#include <span>

#include "hapticctrl/base/time.hpp"

namespace hapticctrl::client::virtuose {
namespace {

/// How long the hand-over waits for the calls still using the old session, so that the old
/// one is destroyed here rather than by an application's thread.
constexpr auto kOldSessionGrace = std::chrono::milliseconds(200);

}  // namespace

void replay(const Settings& s, CommandType command_type, Connection& c) {
  if (s.time_step > 0.0F) {
    c.set_time_step(static_cast<double>(s.time_step));
  }
  c.set_indexing_mode(static_cast<IndexingMode>(s.indexing));
  c.set_force_factor(static_cast<double>(s.force_factor));
  c.set_speed_factor(static_cast<double>(s.speed_factor));
  c.set_base_frame(to_doubles<7>(s.base_frame.data()));
  c.set_observation_frame(to_doubles<7>(s.observation_frame.data()));
  c.set_command_type(command_type);
  if (s.gains) {
    const std::array<double, 4>& g = *s.gains;
    c.set_gains(g[0], g[1], g[2], g[3]);
  }
  if (s.object) {
    c.attach_object(s.object->mass, s.object->inertia);
  }
  if (s.force_limits) {
    c.set_force_limits((*s.force_limits)[0], (*s.force_limits)[1]);
  }
  if (s.watchdog) {
    c.set_watchdog(*s.watchdog);
  }
  if (s.contact_count > 0) {
    c.set_contacts(std::span<const Contact>(s.contacts.data(), s.contact_count));
  }
  if (s.power) {
    try {
      c.set_power(true);
    } catch (const ClientError& e) {
      if (e.code() != ErrorCode::kRejected) {
        throw;
      }
    }
  }
}

Reconnector::Reconnector(Context& context) : context_(context), thread_([this] { run(); }) {}

Reconnector::~Reconnector() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void Reconnector::run() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, kWatchPeriod, [this] { return stopping_; })) {
    std::shared_ptr<Connection> current = context_.link();
    if (current->is_open()) {
      continue;
    }
    const StateSnapshot last = current->snapshot();
    if (last.stopped_in_order()) {
      say("hapticctrl: the controller stopped in order; the session stays closed");
      return;  // an operator's stop ends the application's session, as it ends the demo's
    }
    say(std::string("hapticctrl: ") + last.ending() + "; connecting to the next controller");
    std::shared_ptr<Connection> next = next_session(lock);
    if (!next) {
      return;
    }
    hand_over(current, next);  // `current` is destroyed here, past the grace
  }
}

std::shared_ptr<Connection> Reconnector::next_session(std::unique_lock<std::mutex>& lock) {
  std::string last_said;
  while (!stopping_) {
    lock.unlock();
    try {
      ConnectOptions options;
      options.connect_timeout = kAttemptTimeout;
      auto next = std::make_shared<Connection>(context_.address, options);
      StateSnapshot first;
      if (!next->wait_for_answer(0, kFirstAnswerTimeout, first)) {
        throw ClientError(ErrorCode::kTimeout, "no answer within 2 s of the session's start");
      }
      Settings settings;
      CommandType command_type = CommandType::kNone;
      {
        const std::lock_guard context_lock(context_.mutex);
        settings = context_.settings;
        command_type = context_.command_type;
      }
      replay(settings, command_type, *next);
      lock.lock();
      return next;
    } catch (const std::exception& e) {  // ClientError, or out of memory: try again
      if (last_said != e.what()) {
        last_said = e.what();
        say(std::string("hapticctrl: not yet: ") + e.what());
      }
    }
    lock.lock();
    wake_.wait_for(lock, kRetryPause, [this] { return stopping_; });
  }
  return nullptr;
}

void Reconnector::hand_over(const std::shared_ptr<Connection>& old,
                            const std::shared_ptr<Connection>& next) {
  old->stop_loop();  // returns once a callback that was running on it finished
  {
    const std::lock_guard control(context_.loop_control);
    context_.set_link(next);
    if (context_.loop_running.load()) {
      next->start_loop(periodic_callback(&context_));
    }
  }
  ++sessions_;
  say("hapticctrl: session " + std::to_string(sessions_) + " open with the next controller");
  const auto give_up = hapticctrl::MonotonicClock::now() + kOldSessionGrace;
  while (old.use_count() > 1 && hapticctrl::MonotonicClock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void Reconnector::say(const std::string& line) {
  const std::lock_guard lock(context_.mutex);
  std::fprintf(context_.debug_stream(), "%s\n", line.c_str());
}

}  // namespace hapticctrl::client::virtuose
