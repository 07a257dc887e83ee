// hapticctrl-web: the operator's web view. Serves the page (bridges/web/www), pushes the
// controller's LCM telemetry and the demo's scene to every open page at display rate over
// WebSocket, and forwards the page's commands as LCM HMI messages (the LCM bridge applies them).
// It never touches the core's shared memory: it can run on any host that sees the LCM traffic.
// Exit: 0 done, 1 error, 64 usage.
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/arm_model/arm_model.hpp"
#include "hapticctrl/base/time.hpp"
#include "hapticctrl/lcmtypes/channels.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/web_bridge/model_json.hpp"
#include "hapticctrl/web_bridge/page_gateway.hpp"
#include "hapticctrl/web_bridge/telemetry_view.hpp"
#include "hapticctrl/web_bridge/web_config.hpp"
#include "hapticctrl/web_bridge/web_server.hpp"

namespace {

namespace wb = hapticctrl::web_bridge;
using hapticctrl::MonotonicClock;
using hapticctrl::TimePoint;
using hapticctrl::lcmtypes::Channels;

std::atomic<bool> g_stop{false};
void on_signal(int /*sig*/) {
  g_stop.store(true);
}

/// Publishes the page's accepted requests on the instance's HMI channels.
class LcmHmiPublisher final : public wb::HmiPublisher {
 public:
  LcmHmiPublisher(lcm::LCM& lcm, const Channels& channels) : lcm_(lcm), channels_(channels) {}
  bool publish(const hapticctrl_lcm::hmi_command_t& m) override {
    return lcm_.publish(channels_.hmi_command, &m) == 0;
  }
  bool publish(const hapticctrl_lcm::hmi_force_t& m) override {
    return lcm_.publish(channels_.hmi_force, &m) == 0;
  }

 private:
  lcm::LCM& lcm_;
  const Channels& channels_;
};

/// Decodes the subscribed telemetry into the view; counts what does not decode. Runs on the
/// LCM thread.
class TelemetryInput {
 public:
  // Raw subscriptions decoded here, as hapticctrl-lcm does (Debian LCM 1.3.1's typed
  // member-function subscription trips UBSan inside its own header).
  TelemetryInput(lcm::LCM& lcm, const Channels& ch, wb::TelemetryView& view) : view_(view) {
    using Buffer = lcm::ReceiveBuffer;
    lcm.subscribeFunction(
        ch.arm_state,
        +[](const Buffer* b, const std::string& /*ch*/, TelemetryInput* self) {
          self->deliver<hapticctrl_lcm::arm_state_t>(b, &wb::TelemetryView::on_arm_state);
        },
        this);
    lcm.subscribeFunction(
        ch.coupling,
        +[](const Buffer* b, const std::string& /*ch*/, TelemetryInput* self) {
          self->deliver<hapticctrl_lcm::coupling_t>(b, &wb::TelemetryView::on_coupling);
        },
        this);
    lcm.subscribeFunction(
        ch.cycle_stats,
        +[](const Buffer* b, const std::string& /*ch*/, TelemetryInput* self) {
          self->deliver<hapticctrl_lcm::cycle_stats_t>(b, &wb::TelemetryView::on_cycle_stats);
        },
        this);
    lcm.subscribeFunction(
        ch.events,
        +[](const Buffer* b, const std::string& /*ch*/, TelemetryInput* self) {
          if (!wb::event_strings_sound(b->data, b->data_size)) {
            self->malformed_.fetch_add(1, std::memory_order_relaxed);
            return;
          }
          self->deliver<hapticctrl_lcm::event_t>(b, &wb::TelemetryView::on_event);
        },
        this);
    lcm.subscribeFunction(
        ch.scene,
        +[](const Buffer* b, const std::string& /*ch*/, TelemetryInput* self) {
          self->deliver<hapticctrl_lcm::scene_t>(b, &wb::TelemetryView::on_scene);
        },
        this);
    lcm.subscribeFunction(
        ch.world,
        +[](const Buffer* b, const std::string& /*ch*/, TelemetryInput* self) {
          self->deliver<hapticctrl_lcm::world_t>(b, &wb::TelemetryView::on_world,
                                                 &wb::world_counts_sound);
        },
        this);
  }

  [[nodiscard]] std::uint64_t received() const noexcept { return received_.load(); }
  [[nodiscard]] std::uint64_t malformed() const noexcept { return malformed_.load(); }

 private:
  /// Decodes one message and hands it to the view; what does not decode, or what `sound`
  /// refuses, is counted as malformed and dropped.
  template <typename Message>
  void deliver(const lcm::ReceiveBuffer* rbuf,
               void (wb::TelemetryView::*to_view)(const Message&, TimePoint),
               bool (*sound)(const Message&) = nullptr) {
    Message m{};
    bool decoded = false;
    try {
      decoded = m.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0;
    } catch (const std::exception&) {  // LCM's string decoding may throw bad_alloc
      decoded = false;
    }
    if (!decoded || (sound != nullptr && !sound(m))) {
      malformed_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    received_.fetch_add(1, std::memory_order_relaxed);
    (view_.*to_view)(m, MonotonicClock::now());
  }

  wb::TelemetryView& view_;
  std::atomic<std::uint64_t> received_{0};
  std::atomic<std::uint64_t> malformed_{0};
};

/// What the server asks of the bridge: greetings, page requests, the model and statistics.
class BridgeHandler final : public wb::PageHandler {
 public:
  BridgeHandler(const wb::WebConfig& config, std::string model, wb::TelemetryView& view,
                wb::PageGateway& gateway, const TelemetryInput& input)
      : config_(config), model_(std::move(model)), view_(view), gateway_(gateway), input_(input) {}

  std::vector<std::string> greeting() override {
    const nlohmann::json hello{{"type", "hello"},
                               {"instance", config_.instance},
                               {"remote_commands", config_.allow_remote_commands},
                               {"rate_hz", config_.push_rate_hz}};
    return {hello.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), model_,
            view_.history_frame()};
  }

  std::string on_message(wb::PageSession& page, std::string_view text) override {
    return gateway_.handle(page, text, MonotonicClock::now());
  }

  std::string model() override { return model_; }

  std::string stats() override {
    const auto& c = gateway_.counters();
    const auto get = [](const std::atomic<std::uint64_t>& v) {
      return v.load(std::memory_order_relaxed);
    };
    const nlohmann::json j{{"lcm_received", input_.received()},
                           {"lcm_malformed", input_.malformed()},
                           {"commands_forwarded", get(c.commands_forwarded)},
                           {"forces_forwarded", get(c.forces_forwarded)},
                           {"refused", get(c.refused)},
                           {"malformed", get(c.malformed)},
                           {"out_of_range", get(c.out_of_range)},
                           {"rate_limited", get(c.rate_limited)},
                           {"publish_failed", get(c.publish_failed)}};
    return j.dump();
  }

 private:
  const wb::WebConfig& config_;
  std::string model_;
  wb::TelemetryView& view_;
  wb::PageGateway& gateway_;
  const TelemetryInput& input_;
};

/// Pushes a state frame to every page at the configured rate until told to stop.
void push_loop(wb::TelemetryView& view, wb::WebServer& server, double rate_hz,
               const std::atomic<bool>& running) {
  const auto period = hapticctrl::from_seconds(1.0 / rate_hz);
  auto next = hapticctrl::MonotonicClock::now();
  while (running.load()) {
    next += period;
    const auto now = hapticctrl::MonotonicClock::now();
    if (next < now) {
      next = now + period;  // after a stall: the next slot, never a burst
    }
    std::this_thread::sleep_until(next);
    const std::string frame = view.next_frame(MonotonicClock::now());
    if (server.pages() > 0) {
      server.broadcast(frame);
    }
  }
}

int run(const wb::WebConfig& config) {
  const std::string model_path = config.arm_model_path.empty()
                                     ? hapticctrl::arm_model::default_arm_model_path()
                                     : config.arm_model_path;
  const std::string model = wb::model_json(hapticctrl::arm_model::load_arm_model(model_path));
  lcm::LCM lcm(config.lcm_url);
  if (!lcm.good()) {
    throw std::runtime_error("cannot open LCM at '" + config.lcm_url + "'");
  }
  const Channels ch = Channels::of(config.instance);
  wb::TelemetryView view;
  TelemetryInput input(lcm, ch, view);
  LcmHmiPublisher publisher(lcm, ch);
  wb::PageGateway gateway(publisher, config.allow_remote_commands);
  BridgeHandler handler(config, model, view, gateway, input);
  wb::ServerSettings settings;
  settings.listen = config.listen;
  settings.www_dir = config.www_dir.empty() ? HAPTICCTRL_WEB_WWW_DIR : config.www_dir;
  settings.max_pages = config.max_pages;
  settings.loopback_only = !config.allow_remote;
  wb::WebServer server(settings, handler);
  const std::string address = config.listen.substr(0, config.listen.rfind(':'));
  std::fprintf(stderr,
               "hapticctrl-web: listening on http://%s:%u/ (instance '%s', %s, remote commands "
               "%s)\n",
               address.c_str(), static_cast<unsigned>(server.port()), config.instance.c_str(),
               config.lcm_url.c_str(),
               config.allow_remote_commands ? "enabled" : "disabled (emergency stop only)");
  std::atomic<bool> running{true};
  std::thread pusher([&] { push_loop(view, server, config.push_rate_hz, running); });
  const TimePoint end = hapticctrl::end_after(config.duration_s);
  while (!g_stop.load() && MonotonicClock::now() < end) {
    lcm.handleTimeout(50);
  }
  running.store(false);
  pusher.join();
  if (config.json) {
    std::printf("{\"server\":%s,\"bridge\":%s}\n", server.counters_json().c_str(),
                handler.stats().c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<wb::WebConfig>(
      "hapticctrl-web", argc, argv,
      [](const std::vector<std::string>& args, wb::WebConfig& c) {
        c = wb::WebConfig::parse(args);
        return !c.help;
      },
      &wb::WebConfig::usage,
      [](const wb::WebConfig& c) {
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        std::signal(SIGPIPE, SIG_IGN);  // a browser gone mid-write is an error return, not a signal
        return run(c);
      });
}
