// hapticctrl-dds-listen: what a ROS 2 node would see of a hapticctrl-dds instance, without
// ROS 2: subscribes to every topic of a namespace with ROS 2's type names and QoS (the same
// ros2types/ definitions), for a while, and prints what arrived (counts, rates, the last values,
// the age of each sample against the controller's stamp) as one JSON line. It can send a command
// and an operator wrench back, as `ros2 topic pub` would. Exit: 0 done, 64 usage, 1 error.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/program/options.hpp"
#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/ros2types/participant.hpp"
#include "hapticctrl/ros2types/qos.hpp"

namespace {

namespace r2 = hapticctrl::ros2types;
using hapticctrl::Duration;
using hapticctrl::MonotonicClock;
using hapticctrl::TimePoint;

struct ListenConfig {
  std::string ros_namespace = "/hapticctrl/default";
  std::int32_t domain_id = 0;
  double duration_s = 2.0;
  std::string command;         ///< sent once the bridge's reader is matched
  std::vector<double> wrench;  ///< sent at 100 Hz while listening
  bool help = false;
};

void declare(hapticctrl::program::Options& o, ListenConfig& c) {
  o.custom(
      "--namespace", "NS",
      [&c](const std::string& v) { c.ros_namespace = r2::checked_namespace(v); },
      "ROS 2 namespace of the instance (default /hapticctrl/default)");
  o.number("--domain-id", c.domain_id, std::int32_t{0}, std::int32_t{232}, "DDS domain");
  o.number("--duration", c.duration_s, 0.1, 3600.0, "listen for S seconds (default 2)");
  o.text("--command", c.command, "send this command (power_on, emergency_stop, ...) once");
  o.custom(
      "--wrench", "FX,FY,FZ,TX,TY,TZ",
      [&c](const std::string& v) {
        c.wrench.clear();
        std::size_t at = 0;
        while (at <= v.size() && c.wrench.size() < 6) {
          const std::size_t comma = std::min(v.find(',', at), v.size());
          c.wrench.push_back(hapticctrl::program::number_in<double>(
              "--wrench", v.substr(at, comma - at), -1e6, 1e6));
          at = comma + 1;
        }
        if (c.wrench.size() != 6) {
          throw std::invalid_argument("six comma-separated numbers expected");
        }
      },
      "send this operator wrench at 100 Hz while listening");
}

/// Arrivals on one topic: count, first and last arrival, and each sample's age at arrival.
struct Arrivals {
  std::uint64_t count = 0;
  TimePoint first;
  TimePoint last;
  std::string frame;
  std::vector<double> age_us;

  void saw(const std_msgs_msg_dds__Header_& h, TimePoint now) {
    first = count++ == 0 ? now : first;
    last = now;
    frame = h.frame_id_ != nullptr ? h.frame_id_ : "";
    const std::int64_t stamp = std::int64_t{h.stamp_.sec_} * 1'000'000'000 + h.stamp_.nanosec_;
    age_us.push_back(static_cast<double>(hapticctrl::to_ns(now) - stamp) * 1e-3);
  }
  [[nodiscard]] double rate_hz() const {
    return count > 1 ? static_cast<double>(count - 1) / hapticctrl::to_seconds(last - first) : 0.0;
  }
  [[nodiscard]] double age_quantile(double q) const {
    if (age_us.empty()) {
      return 0.0;
    }
    std::vector<double> sorted = age_us;
    std::sort(sorted.begin(), sorted.end());
    return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
  }
};

void print_topic(const char* name, const char* type, const Arrivals& a) {
  std::printf(
      "\"%s_type\":\"%s\",\"%s_count\":%llu,\"%s_rate_hz\":%.2f,\"%s_frame\":\"%s\","
      "\"%s_age_p50_us\":%.1f,\"%s_age_p99_us\":%.1f,",
      name, type, name, static_cast<unsigned long long>(a.count), name, a.rate_hz(), name,
      a.frame.c_str(), name, a.age_quantile(0.5), name, a.age_quantile(0.99));
}

void print_wrench(const char* name, const geometry_msgs_msg_dds__Wrench_& w) {
  std::printf("\"%s\":[%.6g,%.6g,%.6g,%.6g,%.6g,%.6g],", name, w.force_.x_, w.force_.y_,
              w.force_.z_, w.torque_.x_, w.torque_.y_, w.torque_.z_);
}

/// Whether `writer` has a matched reader within `timeout` (a reliable sample sent before
/// discovery finished would reach nobody).
bool matched(dds_entity_t writer, Duration timeout) {
  const TimePoint until = MonotonicClock::now() + timeout;
  dds_publication_matched_status_t status{};
  while (MonotonicClock::now() < until) {
    if (dds_get_publication_matched_status(writer, &status) == 0 && status.current_count > 0) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

int listen(const ListenConfig& c) {
  r2::Participant p(static_cast<std::uint32_t>(c.domain_id));
  const r2::Qos sensor = r2::sensor_data_qos();
  const r2::Qos commands = r2::command_qos();
  namespace t = r2::topic;
  const auto& ns = c.ros_namespace;
  const dds_entity_t pose_r = p.reader(geometry_msgs_msg_dds__PoseStamped__desc,
                                       r2::dds_topic(ns, t::kHandlePose), sensor.get());
  const dds_entity_t rendered_r = p.reader(geometry_msgs_msg_dds__WrenchStamped__desc,
                                           r2::dds_topic(ns, t::kRenderedWrench), sensor.get());
  const dds_entity_t operator_r = p.reader(geometry_msgs_msg_dds__WrenchStamped__desc,
                                           r2::dds_topic(ns, t::kOperatorWrench), sensor.get());
  const dds_entity_t joints_r = p.reader(sensor_msgs_msg_dds__JointState__desc,
                                         r2::dds_topic(ns, t::kJointStates), sensor.get());
  const dds_entity_t diag_r = p.reader(diagnostic_msgs_msg_dds__DiagnosticArray__desc,
                                       r2::dds_topic(ns, t::kDiagnostics), sensor.get());
  const dds_entity_t command_w =
      p.writer(std_msgs_msg_dds__String__desc, r2::dds_topic(ns, t::kCommand), commands.get());
  const dds_entity_t wrench_w =
      p.writer(geometry_msgs_msg_dds__WrenchStamped__desc,
               r2::dds_topic(ns, t::kOperatorWrenchCommand), commands.get());
  bool command_sent = false;
  if (!c.command.empty() && matched(command_w, std::chrono::seconds(3))) {
    std::string text = c.command;
    std_msgs_msg_dds__String_ m{text.data()};
    command_sent = dds_write(command_w, &m) == 0;
  }
  Arrivals pose;
  Arrivals rendered;
  Arrivals operator_wrench;
  Arrivals joints;
  Arrivals diagnostics;
  geometry_msgs_msg_dds__PoseStamped_ last_pose{};
  geometry_msgs_msg_dds__Wrench_ last_rendered{};
  geometry_msgs_msg_dds__Wrench_ last_operator{};
  std::vector<double> joint_position;
  std::vector<std::string> joint_names;
  std::string diag_text;
  int diag_level = -1;
  const TimePoint end = MonotonicClock::now() + hapticctrl::from_seconds(c.duration_s);
  TimePoint next_wrench{};
  while (MonotonicClock::now() < end) {
    const TimePoint now = MonotonicClock::now();
    r2::take_each<geometry_msgs_msg_dds__PoseStamped_>(pose_r, [&](const auto& m) {
      pose.saw(m.header_, now);
      last_pose = m;
    });
    r2::take_each<geometry_msgs_msg_dds__WrenchStamped_>(rendered_r, [&](const auto& m) {
      rendered.saw(m.header_, now);
      last_rendered = m.wrench_;
    });
    r2::take_each<geometry_msgs_msg_dds__WrenchStamped_>(operator_r, [&](const auto& m) {
      operator_wrench.saw(m.header_, now);
      last_operator = m.wrench_;
    });
    r2::take_each<sensor_msgs_msg_dds__JointState_>(joints_r, [&](const auto& m) {
      joints.saw(m.header_, now);
      joint_position.assign(m.position_._buffer, m.position_._buffer + m.position_._length);
      joint_names.assign(m.name_._buffer, m.name_._buffer + m.name_._length);
    });
    r2::take_each<diagnostic_msgs_msg_dds__DiagnosticArray_>(diag_r, [&](const auto& m) {
      diagnostics.saw(m.header_, now);
      if (m.status_._length > 0) {
        const auto& s = m.status_._buffer[0];
        diag_level = s.level_;
        diag_text = std::string(s.message_) + " |";
        for (std::uint32_t i = 0; i < s.values_._length; ++i) {
          diag_text +=
              std::string(" ") + s.values_._buffer[i].key_ + "=" + s.values_._buffer[i].value_;
        }
      }
    });
    if (c.wrench.size() == 6 && now >= next_wrench) {
      next_wrench = now + std::chrono::milliseconds(10);
      geometry_msgs_msg_dds__WrenchStamped_ w{};
      std::string frame = r2::base_frame(ns);
      w.header_ = {r2::stamp_of(hapticctrl::to_ns(now)), frame.data()};
      w.wrench_ = {{c.wrench[0], c.wrench[1], c.wrench[2]},
                   {c.wrench[3], c.wrench[4], c.wrench[5]}};
      dds_write(wrench_w, &w);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::printf("{");
  print_topic("handle_pose", geometry_msgs_msg_dds__PoseStamped__desc.m_typename, pose);
  print_topic("rendered_wrench", geometry_msgs_msg_dds__WrenchStamped__desc.m_typename, rendered);
  print_topic("operator_wrench", geometry_msgs_msg_dds__WrenchStamped__desc.m_typename,
              operator_wrench);
  print_topic("joint_states", sensor_msgs_msg_dds__JointState__desc.m_typename, joints);
  print_topic("diagnostics", diagnostic_msgs_msg_dds__DiagnosticArray__desc.m_typename,
              diagnostics);
  const auto& q = last_pose.pose_;
  std::printf("\"pose\":[%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g],", q.position_.x_, q.position_.y_,
              q.position_.z_, q.orientation_.x_, q.orientation_.y_, q.orientation_.z_,
              q.orientation_.w_);
  print_wrench("rendered", last_rendered);
  print_wrench("operator", last_operator);
  std::printf("\"joint_position\":[");
  for (std::size_t i = 0; i < joint_position.size(); ++i) {
    std::printf("%s%.6g", i == 0 ? "" : ",", joint_position[i]);
  }
  std::printf("],\"joint_names\":\"");
  for (const auto& n : joint_names) {
    std::printf("%s ", n.c_str());
  }
  std::printf("\",\"diagnostics_level\":%d,\"diagnostics_text\":\"%s\",\"command_sent\":%d}\n",
              diag_level, diag_text.c_str(), command_sent ? 1 : 0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  constexpr const char* kProgram = "hapticctrl-dds-listen";
  constexpr const char* kDescription =
      "What a ROS 2 node sees of a hapticctrl-dds instance, without ROS 2: every topic for a "
      "while, as one JSON line; optionally a command and an operator wrench sent back.";
  return hapticctrl::program::main_skeleton<ListenConfig>(
      kProgram, argc, argv,
      [&](const std::vector<std::string>& args, ListenConfig& c) {
        return hapticctrl::program::parse_into(c, args, kProgram, kDescription, declare);
      },
      [&] { return hapticctrl::program::help_of<ListenConfig>(kProgram, kDescription, declare); },
      listen);
}
