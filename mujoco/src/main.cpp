// hapticctrl-mujoco: a MuJoCo scene as the client. One free body of the model is held by the
// arm's handle through VIRTMECH; the engine steps in real time with the coupling wrench on the
// body and sends the body's pose and twist, and the body's contacts as the controller's local
// contact model (protocol 1.3). Uses only the client library's public API, as an application.
// Exit: 0 done, 1 error, 2 the controller failed safe (--no-reconnect), 64 usage or bad model.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/application.hpp"
#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/lcmtypes/paced_publisher.hpp"
#include "hapticctrl/mujoco/contact_mapping.hpp"
#include "hapticctrl/mujoco/grasp.hpp"
#include "hapticctrl/mujoco/mujoco_options.hpp"
#include "hapticctrl/mujoco/real_time_steps.hpp"
#include "hapticctrl/mujoco/run_summary.hpp"
#include "hapticctrl/mujoco/world.hpp"
#include "hapticctrl/mujoco/world_message.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/program/raw_keyboard.hpp"

namespace {

namespace client = hapticctrl::client;
namespace mj = hapticctrl::mujoco;
using Clock = hapticctrl::MonotonicClock;

std::atomic<bool> g_stop{false};
void on_signal(int /*sig*/) {
  g_stop.store(true);
}

std::int64_t thread_cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

/// After a stall, at most this much world time is run at once; the rest is dropped.
constexpr hapticctrl::Duration kMaxCatchUp = std::chrono::milliseconds(50);
/// With no answer for this long the world pauses (the controller holds the handle meanwhile).
constexpr hapticctrl::Duration kSilentAfter = std::chrono::milliseconds(50);
/// The first connection retries this long (a crashed client holds the session until the
/// bridge's 3 s watchdog frees it); reconnections retry until the run's time is up.
constexpr std::chrono::seconds kFirstConnectPatience{10};

class MujocoRun {
 public:
  explicit MujocoRun(const mj::MujocoOptions& o)
      : o_(o),
        world_(o.model_path, o.body, o.timestep_s),
        steps_(hapticctrl::Duration(std::llround(world_.timestep() * 1e9)), kMaxCatchUp),
        start_(Clock::now()) {
    if (!o.headless && isatty(STDIN_FILENO) != 0) {
      keyboard_.emplace();
    }
    next_status_ = start_;
    if (o.publish_world) {
      world_out_.emplace(o.lcm_url, hapticctrl::lcmtypes::Channels::of(o.instance).world,
                         o.world_rate_hz, "the world");
    }
  }

  int run() {
    std::fprintf(stderr, "hapticctrl-mujoco: %s; '%s', body '%s' (%.3f kg), time step %.3f ms%s\n",
                 mj::engine_version().c_str(), o_.model_path.c_str(), world_.body_name().c_str(),
                 world_.mass(), world_.timestep() * 1e3,
                 world_.has_grip() ? "; g: grip on/off" : "");
    if (world_out_) {
      std::fprintf(stderr, "hapticctrl-mujoco: the scene goes out on LCM, %s (%.0f Hz)\n",
                   world_out_->channel().c_str(), o_.world_rate_hz);
    }
    while (!quit_ && time_left()) {
      std::optional<client::Connection> next = open_session();
      if (!next) {
        ended_ = g_stop.load() ? "signal" : "duration";
        break;
      }
      c_ = std::move(next);
      if (!c_->wait_for_answer(0, std::chrono::seconds(2), s_)) {
        ended_ = "no answer from the controller within 2 s";
      } else {
        run_session();
      }
      if (quit_ || s_.stopped_in_order() || !o_.reconnect || !time_left()) {
        break;
      }
      std::fprintf(stderr, "\nhapticctrl-mujoco: %s; connecting again\n", ended_);
      client::close_quietly(*c_);
      ++reconnects_;
    }
    return finish();
  }

 private:
  [[nodiscard]] double elapsed() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }
  [[nodiscard]] bool time_left() const {
    return !g_stop.load() && (o_.duration_s <= 0.0 || elapsed() < o_.duration_s);
  }

  /// VirtuoseAPI's initialisation: frames, factors, the engine's time step, VIRTMECH with the
  /// body's mass and inertia, power-on.
  void initialise(client::Connection& c) const {
    const client::Pose7 identity{0, 0, 0, 0, 0, 0, 1};
    c.set_base_frame(identity);
    c.set_observation_frame(identity);
    c.set_force_factor(1.0);
    c.set_speed_factor(1.0);
    c.set_time_step(world_.timestep());
    c.set_command_type(client::CommandType::kVirtmech);
    c.attach_object(world_.mass(), world_.inertia());
    if (o_.power_on) {
      c.set_power(true);
    }
  }

  /// A session, or nothing once the run's time is up (refusals retried: application.hpp).
  std::optional<client::Connection> open_session() {
    client::ConnectOptions connect;
    connect.client_name = "hapticctrl-mujoco";
    client::RetryPolicy policy;
    policy.patience = reconnects_ > 0 ? std::chrono::seconds(0) : kFirstConnectPatience;
    policy.reconnecting = reconnects_ > 0;
    return client::connect_retrying(
        client::Address::parse(o_.server), connect,
        [this](client::Connection& c) { initialise(c); }, [this] { return time_left(); }, policy,
        [](const client::ClientError& e) {
          std::fprintf(stderr, "hapticctrl-mujoco: %s; retrying\n", e.what());
        });
  }

  /// The scene is held where the handle is; then steps until the session or the run ends.
  void run_session() {
    grasp_ = mj::Grasp::between(world_.pose(), s_.handle_pose);
    if (reconnects_ == 0) {
      std::fprintf(stderr, "hapticctrl-mujoco: ready: VIRTMECH, %s; %s\n",
                   o_.power_on ? "power on requested" : "power left to the HMI",
                   o_.report_contacts && !contacts_unsupported_
                       ? "contacts reported to the controller"
                       : "contacts rendered by the coupling alone");
    } else {
      std::fprintf(stderr, "hapticctrl-mujoco: reconnected (%llu)\n",
                   static_cast<unsigned long long>(reconnects_));
    }
    if (s_.awaiting_operator() && o_.power_on) {
      std::fprintf(stderr,
                   "hapticctrl-mujoco: the controller restarted after a fault and refuses this "
                   "client's power-on: waiting for the operator to power the arm on (the "
                   "panel's p, or hapticctrl-hmi power-on)\n");
    }
    hapticctrl::TimePoint last_answer = Clock::now();
    steps_.start(last_answer);
    if (!stepping_since_) {
      stepping_since_ = Clock::now();
    }
    ended_ = "duration";
    while (!quit_) {
      if (g_stop.load()) {
        ended_ = "signal";
        quit_ = true;
        break;
      }
      if (!time_left()) {
        quit_ = true;
        break;
      }
      const auto wait =
          std::clamp(steps_.next_due() - Clock::now(), hapticctrl::Duration::zero(), kSilentAfter);
      const bool answered = c_->wait_for_answer(s_.cycle, wait, s_);
      if (!c_->is_open() || s_.session_over()) {
        ended_ = s_.ending();
        break;
      }
      const hapticctrl::TimePoint now = Clock::now();
      last_answer = answered ? now : last_answer;
      if (now - last_answer > kSilentAfter) {
        steps_.pause(now);
        continue;
      }
      poll_keys();
      if (const std::uint64_t due = steps_.due(now); due > 0) {
        step(due);
      }
      print_status_when_due();
    }
  }

  void poll_keys() {
    for (int key = keyboard_ ? keyboard_->poll() : -1; key >= 0; key = keyboard_->poll()) {
      if (key == 'q') {
        ended_ = "quit";
        quit_ = true;
      } else if (key == 'r') {
        world_.reset();
        world_.set_grip(gripping_);
        grasp_ = mj::Grasp::between(world_.pose(), s_.handle_pose);
      } else if (key == 'g' && world_.has_grip()) {
        gripping_ = !gripping_;
        world_.set_grip(gripping_);
        std::fprintf(stderr, "%shapticctrl-mujoco: grip %s\n", keyboard_ ? "\r\n" : "",
                     gripping_ ? "on" : "off");
      }
    }
  }

  /// `due` engine steps with the coupling wrench of the last answer; the body's state and its
  /// contacts go out once after them.
  void step(std::uint64_t due) {
    for (std::uint64_t k = 0; k < due; ++k) {
      const std::int64_t before = thread_cpu_ns();
      world_.step(s_.coupling_wrench);
      load_.add(thread_cpu_ns() - before);
    }
    report_contacts();
    (void)c_->send_object_state(grasp_.to_client(world_.pose()), world_.twist());
    publish_world_when_due();
  }

  /// The scene for the web view, at --world-rate.
  void publish_world_when_due() {
    const hapticctrl::TimePoint now = Clock::now();
    if (!world_out_ || !world_out_->due(now)) {
      return;
    }
    const mj::WorldRun run{steps_.run(), steps_per_second(), hapticctrl::to_ns(now) / 1000};
    (void)world_out_->publish(mj::to_world_message(
        world_, grasp_, std::span(contacts_out_.data(), contacts_count_), run));
  }

  /// The body's contacts (and those it is near) in the client's frame, deepest first.
  void report_contacts() {
    if (!o_.report_contacts || contacts_unsupported_) {
      return;
    }
    const client::LinkStatistics link = c_->statistics();
    const client::Pose7 body = grasp_.to_client(world_.pose());
    const double lead = std::hypot(s_.handle_pose[0] - body[0], s_.handle_pose[1] - body[1],
                                   s_.handle_pose[2] - body[2]);
    world_.set_report_distance(client::contact_report_distance(link) + lead);
    std::array<mj::EngineContact, client::kMaxContacts> found{};
    const std::size_t n = world_.contacts(found);
    std::array<client::Contact, client::kMaxContacts>& out = contacts_out_;
    const std::size_t count = mj::to_client_contacts(std::span(found.data(), n), world_.timestep(),
                                                     link.max_contact_stiffness, out);
    for (std::size_t i = 0; i < count; ++i) {
      out[i].point = grasp_.point_to_client(out[i].point);
    }
    contacts_count_ = count;
    reported_ += count > 0 ? 1 : 0;
    const client::ContactResult r = c_->set_contacts(std::span(out.data(), count));
    if (r == client::ContactResult::kUnsupported) {
      contacts_unsupported_ = true;
      std::fprintf(stderr,
                   "hapticctrl-mujoco: the controller speaks no protocol 1.3: contacts are "
                   "rendered by the coupling alone (soft behind a delay)\n");
    } else if (r != client::ContactResult::kAccepted && !refusal_said_) {
      refusal_said_ = true;
      std::fprintf(stderr, "hapticctrl-mujoco: the controller refuses a contact (%d)\n",
                   static_cast<int>(r));
    }
  }

  /// Steps run per second of wall clock since the world first stepped (the connection's set-up
  /// before it is not the engine's; a reconnection's gap after it is, as the world stood still).
  [[nodiscard]] double steps_per_second() const {
    if (!stepping_since_) {
      return 0.0;
    }
    const double t = std::chrono::duration<double>(Clock::now() - *stepping_since_).count();
    return t > 0.0 ? static_cast<double>(steps_.run()) / t : 0.0;
  }

  void print_status_when_due() {
    if (o_.status_ms <= 0 || Clock::now() < next_status_) {
      return;
    }
    next_status_ += std::chrono::milliseconds(o_.status_ms);
    print_status(keyboard_ ? "\r" : "\n");
  }

  void print_status(const char* end) const {
    const client::Pose7 p = world_.pose();
    const std::array<double, 3> f = world_.contact_force();
    std::fprintf(stderr,
                 "t=%6.2f s  body (%.4f %.4f %.4f) m  contact %.2f N  coupling (%.2f %.2f %.2f) "
                 "N  %.0f steps/s  cpu %.0f us/step%s",
                 elapsed(), p[0], p[1], p[2], std::hypot(f[0], f[1], f[2]), s_.coupling_wrench[0],
                 s_.coupling_wrench[1], s_.coupling_wrench[2], steps_per_second(), load_.mean_us(),
                 end);
  }

  int finish() {
    const bool failed_safe = s_.fail_safe();
    if (c_) {
      client::close_quietly(*c_);
    }
    print_status("\n");
    std::fprintf(stderr,
                 "hapticctrl-mujoco: ended (%s) after %llu steps (%llu dropped after stalls, %llu "
                 "paused on a silent link), %llu reconnections\n",
                 ended_, static_cast<unsigned long long>(steps_.run()),
                 static_cast<unsigned long long>(steps_.dropped()),
                 static_cast<unsigned long long>(steps_.paused()),
                 static_cast<unsigned long long>(reconnects_));
    if (o_.json) {
      print_json();
    }
    if (!c_) {
      return 1;
    }
    return failed_safe && !o_.reconnect ? 2 : 0;
  }

  void print_json() const {
    mj::RunSummary r;
    r.ended = ended_;
    r.body = world_.body_name();
    r.mass = world_.mass();
    r.timestep = world_.timestep();
    r.body_pose = world_.pose();
    r.contact_force = world_.contact_force();
    r.coupling_wrench = s_.coupling_wrench;
    r.steps = steps_.run();
    r.steps_per_second = steps_per_second();
    r.steps_dropped = steps_.dropped();
    r.steps_paused = steps_.paused();
    r.catch_ups = steps_.catch_ups();
    r.load = load_;
    r.contact_reports = reported_;
    r.contacts_supported = !contacts_unsupported_;
    r.instabilities = world_.instabilities();
    r.reconnections = reconnects_;
    r.powered = s_.powered();
    r.gripping = gripping_;
    r.bodies = world_.free_bodies();
    r.joints = world_.joints();
    std::printf("%s\n", mj::summary_json(r).c_str());
  }

  const mj::MujocoOptions& o_;
  mj::World world_;
  mj::RealTimeSteps steps_;
  mj::Grasp grasp_;
  const Clock::time_point start_;
  std::optional<hapticctrl::program::RawKeyboard> keyboard_;
  Clock::time_point next_status_;
  std::optional<Clock::time_point> stepping_since_;
  mj::EngineLoad load_;
  std::uint64_t reconnects_ = 0;
  std::uint64_t reported_ = 0;
  const char* ended_ = "duration";
  bool quit_ = false;
  bool contacts_unsupported_ = false;
  bool refusal_said_ = false;
  bool gripping_ = false;
  std::optional<client::Connection> c_;
  client::StateSnapshot s_;
  std::array<client::Contact, client::kMaxContacts> contacts_out_{};  ///< as last reported
  std::size_t contacts_count_ = 0;
  std::optional<hapticctrl::lcmtypes::PacedPublisher<hapticctrl_lcm::world_t>> world_out_;
};

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<mj::MujocoOptions>(
      "hapticctrl-mujoco", argc, argv,
      [](const std::vector<std::string>& args, mj::MujocoOptions& o) {
        o = mj::MujocoOptions::parse(args);
        return !o.help;
      },
      &mj::MujocoOptions::usage,
      [](const mj::MujocoOptions& o) {
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        return MujocoRun(o).run();
      });
}
