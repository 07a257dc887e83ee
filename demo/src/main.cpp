// hapticctrl-demo: the seeds' test client. A mobile sphere, coupled to the arm through the
// client library in VIRTMECH mode, next to a fixed sphere; the client integrates both at its
// time step (one step per controller answer) and sends the mobile sphere's state back.
// A session lost with its link, or ended by a controller that failed safe, is opened again
// (--no-reconnect: the demo exits instead).
// Exit: 0 done, 1 error, 2 the controller failed safe (--no-reconnect), 64 usage.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <fstream>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/application.hpp"
#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/demo/demo_input.hpp"
#include "hapticctrl/demo/demo_options.hpp"
#include "hapticctrl/demo/demo_report.hpp"
#include "hapticctrl/demo/scene_publisher.hpp"
#include "hapticctrl/demo/sphere_scene.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/program/raw_keyboard.hpp"

namespace {

namespace client = hapticctrl::client;
namespace demo = hapticctrl::demo;
namespace program = hapticctrl::program;
using Clock = hapticctrl::MonotonicClock;

std::atomic<bool> g_stop{false};
void on_signal(int /*sig*/) {
  g_stop.store(true);
}

/// The seeds' initialisation: references and frames, units and factors, time step, command
/// type, object attach, power-on.
void initialise(client::Connection& c, const demo::DemoOptions& o, double time_step) {
  const client::Pose7 identity{0, 0, 0, 0, 0, 0, 1};
  c.set_base_frame(identity);
  c.set_observation_frame(identity);
  c.set_force_factor(1.0);
  c.set_speed_factor(1.0);
  c.set_time_step(time_step);
  if (o.impedance) {
    c.set_command_type(client::CommandType::kImpedance);
  } else {
    c.set_command_type(client::CommandType::kVirtmech);
    const double inertia = o.scene.inertia();
    c.attach_object(o.scene.mass, {inertia, inertia, inertia});
  }
  if (o.power_on) {
    c.set_power(true);
  }
}

/// The scene starts with the mobile sphere on the handle and the fixed one `gap` away along +x.
demo::SphereScene scene_at(const client::StateSnapshot& s, const demo::DemoOptions& o) {
  demo::SceneConfig config = o.scene;
  demo::SphereState start;
  start.position = {s.handle_pose[0], s.handle_pose[1], s.handle_pose[2]};
  start.orientation =
      Eigen::Quaterniond(s.handle_pose[6], s.handle_pose[3], s.handle_pose[4], s.handle_pose[5])
          .normalized();
  const double reach = config.obstacle == demo::Obstacle::kWall
                           ? config.mobile_radius + o.gap
                           : config.fixed_radius + config.mobile_radius + o.gap;
  config.fixed_center = start.position + config.toward * reach;
  return {config, start};
}

/// At most this many steps are integrated for one answer (a longer gap pauses the world).
constexpr std::uint64_t kMaxCatchUpSteps = 20;
/// The first connection retries this long: a client that crashed holds the session until the
/// bridge's watchdog (3 s) frees it. Reconnections retry until the demo's time is up.
constexpr std::chrono::seconds kFirstConnectPatience{10};
constexpr std::chrono::seconds kRetryForever{0};

/// A session, initialised the seeds' way, or nothing when `may_continue` turns false or
/// `patience` (0: unbounded, and a refused setup retried too: reconnecting) runs out; refusals
/// retried as application.hpp says.
template <typename MayContinue>
std::optional<client::Connection> open_session(const demo::DemoOptions& o, MayContinue may_continue,
                                               std::chrono::seconds patience) {
  client::ConnectOptions connect;
  connect.client_name = "hapticctrl-demo";
  client::RetryPolicy policy;
  policy.patience = patience;
  policy.reconnecting = patience.count() == 0;
  return client::connect_retrying(
      client::Address::parse(o.server), connect,
      [&o](client::Connection& c) {
        initialise(c, o, static_cast<double>(c.controller_period_ns()) / 1e9);
      },
      may_continue, policy,
      [](const client::ClientError& e) {
        std::fprintf(stderr, "hapticctrl-demo: %s; retrying\n", e.what());
      });
}

/// One run of the demo: its inputs and outputs (script, keyboard, log, scene channel), the
/// sessions it opens one after the other, and their steps.
class DemoRun {
 public:
  explicit DemoRun(const demo::DemoOptions& o) : o_(o), start_(Clock::now()) {
    o.scene.validate();
    if (!o.script_path.empty()) {
      script_.emplace(demo::DemoScript::load(o.script_path));
    }
    if (!o.log_path.empty()) {
      log_.open(o.log_path);
      if (!log_) {
        throw std::runtime_error("cannot write the log '" + o.log_path + "'");
      }
      demo::write_log_header(log_);
    }
    if (o.publish_scene) {
      scene_out_.emplace(o.lcm_url, o.instance, o.scene_rate_hz);
    }
    if (!o.headless && isatty(STDIN_FILENO) != 0) {
      keyboard_.emplace();
    }
    next_status_ = start_;
  }

  /// Sessions until the duration, a signal, a quit, an orderly stop or (without reconnection)
  /// a session that ends abnormally. Returns the exit status.
  int run() {
    while (!quit_ && time_left()) {
      std::optional<client::Connection> next = open_session(
          o_, [this] { return time_left(); },
          reconnects_ > 0 ? kRetryForever : kFirstConnectPatience);
      if (!next) {
        ended_ = g_stop.load() ? "signal" : "duration";
        break;
      }
      c_ = std::move(next);
      bool orderly_stop = false;
      if (c_->wait_for_answer(0, std::chrono::seconds(2), s_)) {
        scene_.emplace(scene_at(s_, o_));  // a new session starts with the sphere at the handle
        announce();
        run_session();
        orderly_stop = s_.stopped_in_order();
      } else if (o_.reconnect) {
        ended_ = "no answer from the controller within 2 s";  // failing safe again, or stalled
      } else {
        throw std::runtime_error("no answer from the controller within 2 s");
      }
      if (quit_ || orderly_stop || !o_.reconnect || !time_left()) {
        break;
      }
      std::fprintf(stderr, "\nhapticctrl-demo: %s; connecting again\n", ended_);
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

  void announce() const {
    const double dt = static_cast<double>(c_->controller_period_ns()) / 1e9;
    if (reconnects_ == 0) {
      std::fprintf(stderr,
                   "hapticctrl-demo: ready: %s, %.3f kg sphere, time step %.3f ms, %s; "
                   "fixed %s at (%.4f %.4f %.4f)\n",
                   o_.impedance ? "IMPEDANCE" : "VIRTMECH", o_.scene.mass, dt * 1e3,
                   o_.power_on ? "power on requested" : "power left to the HMI",
                   o_.scene.obstacle == demo::Obstacle::kWall ? "wall" : "sphere",
                   scene_->config().fixed_center.x(), scene_->config().fixed_center.y(),
                   scene_->config().fixed_center.z());
    } else {
      std::fprintf(stderr, "hapticctrl-demo: reconnected (%llu)\n",
                   static_cast<unsigned long long>(reconnects_));
    }
    if (s_.awaiting_operator() && o_.power_on) {
      std::fprintf(stderr,
                   "hapticctrl-demo: the controller restarted after a fault and refuses this "
                   "client's power-on: waiting for the operator to power the arm on (the "
                   "panel's p, or hapticctrl-hmi power-on)\n");
    }
  }

  /// Steps the scene on every answer until the session ends or the run does.
  void run_session() {
    const double dt = static_cast<double>(c_->controller_period_ns()) / 1e9;
    std::uint64_t last_cycle = s_.cycle;
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
      const bool answered = c_->wait_for_answer(s_.cycle, std::chrono::milliseconds(100), s_);
      if (!c_->is_open() || s_.session_over()) {
        ended_ = s_.ending();
        break;
      }
      if (answered) {
        step(dt, last_cycle);
      }
    }
  }

  /// One answer: inputs, the scene advanced by the controller's time since the last answer,
  /// the object state sent back, the outputs.
  void step(double dt, std::uint64_t& last_cycle) {
    const double t = elapsed();
    std::array<double, 3> obstacle_move{};
    if (script_ && script_->advance(t, applied_, obstacle_move) == demo::InputResult::kQuit) {
      ended_ = "script";
      quit_ = true;
    }
    scene_->move_obstacle(Eigen::Vector3d(obstacle_move[0], obstacle_move[1], obstacle_move[2]));
    for (int key = keyboard_ ? keyboard_->poll() : -1; key >= 0; key = keyboard_->poll()) {
      if (demo::apply_demo_key(key, applied_) == demo::InputResult::kQuit) {
        ended_ = "quit";
        quit_ = true;
      }
    }
    // One step per controller cycle since the last answer (answers lost or late do not slow the
    // world down), at most kMaxCatchUpSteps (a longer gap pauses the world rather than
    // integrating it blind).
    const std::uint64_t cycles =
        std::clamp<std::uint64_t>(s_.cycle - last_cycle, 1, kMaxCatchUpSteps);
    last_cycle = s_.cycle;
    if (o_.impedance) {
      render_contact();
    } else {
      for (std::uint64_t k = 0; k < cycles; ++k) {
        scene_->step(s_.coupling_wrench, applied_.wrench, dt);
      }
      report_contact();
      (void)c_->send_object_state(scene_->pose(), scene_->twist());
    }
    ++steps_;
    if (const hapticctrl::TimePoint now = Clock::now(); scene_out_ && scene_out_->due(now)) {
      (void)scene_out_->publish(demo::to_scene_message(*scene_, applied_, c_->statistics(), steps_,
                                                       hapticctrl::to_ns(now) / 1000));
    }
    if (log_.is_open()) {
      demo::write_log_row(log_, t, s_, *scene_, applied_);
    }
    if (o_.status_ms > 0 && Clock::now() >= next_status_) {
      next_status_ += std::chrono::milliseconds(o_.status_ms);
      demo::print_status(stderr, t, s_, *scene_, keyboard_ ? "\r" : "\n");
    }
  }

  /// VIRTMECH: the spheres' contact (or none) goes out with the object state.
  void report_contact() {
    if (!o_.report_contacts) {
      return;
    }
    // The controller renders the contact on the handle, which the coupling lets lead the
    // object (by centimetres behind a long link, where the coupling is soft): reported only
    // from 5 mm of the object's gap, the handle met no surface and was found inside it when the
    // report came. So the gap that counts is the handle's too, and the reach over the round
    // trip is added as for an IMPEDANCE surface.
    const client::LinkStatistics link = c_->statistics();
    const double near = client::contact_report_distance(link);
    const Eigen::Vector3d handle(s_.handle_pose[0], s_.handle_pose[1], s_.handle_pose[2]);
    std::optional<client::Contact> contact = scene_->contact_report_toward(
        handle, std::numeric_limits<double>::infinity(), link.max_contact_stiffness);
    if (contact) {
      const client::Pose7 object = scene_->pose();
      double lead = 0.0;  // how far the handle is ahead of the object toward the surface
      for (std::size_t i = 0; i < 3; ++i) {
        lead -= (s_.handle_pose[i] - object[i]) * contact->normal[i];
      }
      if (contact->distance - std::max(0.0, lead) > near) {
        contact.reset();
      }
    }
    const std::span<const client::Contact> contacts =
        contact ? std::span<const client::Contact>(&*contact, 1)
                : std::span<const client::Contact>();
    if (const client::ContactResult r = c_->set_contacts(contacts);
        r != client::ContactResult::kAccepted && r != client::ContactResult::kUnsupported &&
        !contact_refusal_said_) {
      contact_refusal_said_ = true;
      std::fprintf(stderr, "hapticctrl-demo: the controller refuses the contact (%d)\n",
                   static_cast<int>(r));
    }
  }

  /// IMPEDANCE: the handle is the sphere; the fixed one's contact force (and the operator's
  /// push from the keyboard or script) is the wrench to render.
  /// The fixed sphere's or the wall's surface goes out with the wrench (protocol 1.3): the
  /// controller renders it at its own rate in place of this push out of it.
  void render_contact() {
    scene_->follow(s_.handle_pose, s_.handle_twist);
    const Eigen::Vector3d f = scene_->contact_force();
    client::Vector6 wrench = applied_.wrench;
    for (int i = 0; i < 3; ++i) {
      wrench[static_cast<std::size_t>(i)] += f(i);
    }
    if (o_.report_contacts) {
      // Known before the handle can reach it: a surface reported only from 5 mm on came and
      // went with the handle's delayed image at 100 ms one way, and the handle went through the
      // wall between reports (2 m/s, 2026-12-03). The controller renders it only once touched.
      const client::LinkStatistics link = c_->statistics();
      const double near = client::contact_report_distance(link);
      const std::optional<client::Contact> surface =
          scene_->surface_for_center(near, link.max_contact_stiffness);
      (void)c_->set_contacts(surface ? std::span<const client::Contact>(&*surface, 1)
                                     : std::span<const client::Contact>());
    }
    (void)c_->send_wrench(wrench);
  }

  int finish() {
    if (keyboard_) {
      std::fprintf(stderr, "\n");
    }
    if (!c_ || !scene_) {
      std::fprintf(stderr, "hapticctrl-demo: ended (%s) before any session\n", ended_);
      return 1;
    }
    const bool failed_safe = s_.fail_safe();
    client::close_quietly(*c_);
    demo::print_status(stderr, elapsed(), s_, *scene_, "\n");
    std::fprintf(stderr, "hapticctrl-demo: ended (%s) after %llu steps, %llu reconnections\n",
                 ended_, static_cast<unsigned long long>(steps_),
                 static_cast<unsigned long long>(reconnects_));
    if (o_.json) {
      demo::print_summary_json(stdout, s_, *scene_, c_->statistics(), steps_, reconnects_, ended_);
    }
    return failed_safe && !o_.reconnect ? 2 : 0;
  }

  const demo::DemoOptions& o_;
  const Clock::time_point start_;
  std::optional<demo::DemoScript> script_;
  std::ofstream log_;
  std::optional<demo::ScenePublisher> scene_out_;
  std::optional<program::RawKeyboard> keyboard_;
  demo::AppliedWrench applied_;
  Clock::time_point next_status_;
  std::uint64_t steps_ = 0;
  std::uint64_t reconnects_ = 0;
  const char* ended_ = "duration";
  bool quit_ = false;
  bool contact_refusal_said_ = false;
  std::optional<client::Connection> c_;
  client::StateSnapshot s_;
  std::optional<demo::SphereScene> scene_;
};

int run(const demo::DemoOptions& o) {
  return DemoRun(o).run();
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<demo::DemoOptions>(
      "hapticctrl-demo", argc, argv,
      [](const std::vector<std::string>& args, demo::DemoOptions& c) {
        c = demo::DemoOptions::parse(args);
        return !c.help;
      },
      &demo::DemoOptions::usage,
      [](const demo::DemoOptions& c) {
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        return run(c);
      });
}
