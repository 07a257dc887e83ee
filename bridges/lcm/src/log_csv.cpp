// Implements log_csv.hpp: offline analysis: an LCM log (lcm-logger) to one CSV file per hapticctrl
// channel.
#include "hapticctrl/lcm_bridge/log_csv.hpp"

#include <fstream>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "hapticctrl/lcmtypes/regions.hpp"
#include "hapticctrl/shm/payload_text.hpp"
#include "hapticctrl_lcm/coupling_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"
#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"
#include "hapticctrl_lcm/scene_t.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

using Row = std::ostringstream;

/// Column names "<prefix><suffix>" for each suffix.
std::string columns(const std::string& prefix, std::initializer_list<const char*> suffixes) {
  std::string out;
  for (const char* s : suffixes) {
    out += "," + prefix + s;
  }
  return out;
}
const std::initializer_list<const char*> kPose = {"x", "y", "z", "qx", "qy", "qz", "qw"};
const std::initializer_list<const char*> kVec6 = {"x", "y", "z", "rx", "ry", "rz"};

template <typename T, std::size_t N>
void put(Row& r, const T (&values)[N]) {  // NOLINT(*-avoid-c-arrays): lcm-gen's arrays
  for (const T& v : values) {
    r << ',' << v;
  }
}

/// CSV text field: quoted, quotes doubled.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return out + "\"";
}

struct Topic {
  std::string header;
  std::function<bool(const void*, int, Row&)> row;  ///< false: did not decode
};

template <typename M>
bool decode(const void* data, int size, M& m) {
  try {
    return m.decode(data, 0, size) >= 0;
  } catch (...) {
    return false;
  }
}

/// A region LCM carries one for one: the message read back into its payload and written through
/// the payload's field table, after the message's utime.
template <typename M, typename P>
Topic region(P (*from)(const M&)) {
  return {"utime," + shm::csv_header<P>(), [from](const void* d, int n, Row& r) {
            M m{};
            if (!decode(d, n, m)) {
              return false;
            }
            r << m.utime << ',' << shm::csv_row(from(m));
            return true;
          }};
}

std::map<std::string, Topic> topics() {
  std::map<std::string, Topic> t;
  t["arm_state"] = region<hapticctrl_lcm::arm_state_t>(lcmtypes::from_arm_state);
  t["cycle_stats"] = region<hapticctrl_lcm::cycle_stats_t>(lcmtypes::from_cycle_stats);
  t["bridge_stats"] = region<hapticctrl_lcm::bridge_stats_t>(lcmtypes::from_bridge_stats);
  t["coupling"] = {
      "utime,cycle,session_id,command_type,object_attached" + columns("object_", kPose) +
          columns("object_twist_", kVec6) + columns("object_wrench_", kVec6) +
          columns("client_handle_", kPose) +
          ",client_sequence,client_age_ms,client_stale,vpr_stale_cycles,"
          "sample_age_ms,loop_delay_ms,link_delay_ms,link_jitter_ms,link_loss" +
          columns("gain_", {"k_lin", "b_lin", "k_ang", "b_ang"}) + ",contacts" +
          columns("surface_point_", {"x", "y", "z"}) + columns("surface_normal_", {"x", "y", "z"}) +
          ",surface_depth_mm,surface_force,surface_hidden_mm,surface_withheld,contact_age_ms",
      [](const void* d, int n, Row& r) {
        hapticctrl_lcm::coupling_t m{};
        if (!decode(d, n, m)) {
          return false;
        }
        r << m.utime << ',' << m.cycle << ',' << m.session_id << ',' << m.command_type << ','
          << (m.object_attached ? 1 : 0);
        put(r, m.object_pose);
        put(r, m.object_twist);
        put(r, m.object_wrench);
        put(r, m.client_handle_pose);
        r << ',' << m.client_sequence << ',' << m.client_age_ms << ',' << (m.client_stale ? 1 : 0)
          << ',' << m.vpr_stale_cycles << ',' << m.sample_age_ms << ',' << m.loop_delay_ms << ','
          << m.link_delay_ms << ',' << m.link_jitter_ms << ',' << m.link_loss;
        put(r, m.gains);
        r << ',' << m.contacts;
        put(r, m.surface_point);
        put(r, m.surface_normal);
        r << ',' << m.surface_depth_mm << ',' << m.surface_force << ',' << m.surface_hidden_mm
          << ',' << m.surface_withheld << ',' << m.contact_age_ms;
        return true;
      }};
  t["events"] = {"utime,index,cycle,time_ns,kind,code,value,text,lost_before",
                 [](const void* d, int n, Row& r) {
                   hapticctrl_lcm::event_t m{};
                   if (!decode(d, n, m)) {
                     return false;
                   }
                   r << m.utime << ',' << m.index << ',' << m.cycle << ',' << m.time_ns << ','
                     << m.kind << ',' << m.code << ',' << m.value << ',' << quoted(m.text) << ','
                     << m.lost_before;
                   return true;
                 }};
  t["scene"] = {"utime,steps" + columns("fixed_", {"x", "y", "z"}) + ",fixed_radius" +
                    columns("mobile_", kPose) + ",mobile_radius" +
                    columns("contact_f", {"x", "y", "z"}) + ",penetration" +
                    columns("applied_", kVec6) +
                    ",rtt_last_us,rtt_mean_us,rtt_max_us,answers_received,answers_lost",
                [](const void* d, int n, Row& r) {
                  hapticctrl_lcm::scene_t m{};
                  if (!decode(d, n, m)) {
                    return false;
                  }
                  r << m.utime << ',' << m.steps;
                  put(r, m.fixed_center);
                  r << ',' << m.fixed_radius;
                  put(r, m.mobile_pose);
                  r << ',' << m.mobile_radius;
                  put(r, m.contact_force);
                  r << ',' << m.penetration;
                  put(r, m.applied_wrench);
                  r << ',' << m.rtt_last_us << ',' << m.rtt_mean_us << ',' << m.rtt_max_us << ','
                    << m.answers_received << ',' << m.answers_lost;
                  return true;
                }};
  t["hmi_command"] = {"utime,command,origin", [](const void* d, int n, Row& r) {
                        hapticctrl_lcm::hmi_command_t m{};
                        if (!decode(d, n, m)) {
                          return false;
                        }
                        r << m.utime << ',' << m.command << ',' << quoted(m.origin);
                        return true;
                      }};
  t["hmi_force"] = {"utime" + columns("wrench_", kVec6) + ",origin",
                    [](const void* d, int n, Row& r) {
                      hapticctrl_lcm::hmi_force_t m{};
                      if (!decode(d, n, m)) {
                        return false;
                      }
                      r << m.utime;
                      put(r, m.wrench);
                      r << ',' << quoted(m.origin);
                      return true;
                    }};
  return t;
}

}  // namespace

CsvReport log_to_csv(const std::string& log_path, const std::string& out_dir) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) {
    throw std::runtime_error("cannot read LCM log '" + log_path + "'");
  }
  const std::map<std::string, Topic> known = topics();
  std::map<std::string, std::unique_ptr<std::ofstream>> files;
  CsvReport report;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    const std::string& ch = ev->channel;
    const auto dot = ch.rfind('.');
    const auto it = ch.rfind("hapticctrl.", 0) == 0 && dot != std::string::npos
                        ? known.find(ch.substr(dot + 1))
                        : known.end();
    if (it == known.end()) {
      ++report.skipped;
      continue;
    }
    Row row;
    row.precision(9);
    if (!it->second.row(ev->data, ev->datalen, row)) {
      ++report.undecodable;
      continue;
    }
    auto& file = files[ch];
    if (!file) {
      std::string path = out_dir;
      path += "/";
      path += ch;
      path += ".csv";
      file = std::make_unique<std::ofstream>(path);
      if (!*file) {
        throw std::runtime_error("cannot write '" + path + "'");
      }
      *file << it->second.header << '\n';
    }
    *file << row.str() << '\n';
    ++report.rows[ch + ".csv"];
  }
  return report;
}

}  // namespace hapticctrl::lcm_bridge
