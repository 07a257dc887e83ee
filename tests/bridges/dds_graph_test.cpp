// Tests of dds_bridge/graph.hpp: the bridge as a node of ROS 2's graph. A second participant
// started afterwards does what a graph tool (ros2 node info, rqt_graph) does: it reads
// ros_discovery_info and matches each GID with the endpoint DDS discovered under that GUID.
#include "hapticctrl/dds_bridge/graph.hpp"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/ros2types/qos.hpp"
#include "support/dds_loopback.hpp"

namespace hapticctrl::dds_bridge {
namespace {

using namespace std::chrono_literals;

using Gid = std::array<unsigned char, 24>;

Gid copy(const rmw_dds_common_msg_dds__Gid_& g) {
  Gid out{};
  std::memcpy(out.data(), g.data_, out.size());
  return out;
}

Gid padded(const dds_guid_t& guid) {
  Gid out{};
  std::memcpy(out.data(), guid.v, sizeof guid.v);
  return out;
}

/// One node of an announcement, as a graph tool keeps it.
struct Node {
  std::string ns;
  std::string name;
  std::vector<Gid> readers;
  std::vector<Gid> writers;
};

struct Announcement {
  Gid participant{};
  std::vector<Node> nodes;
};

std::vector<Gid> gids(const auto& seq) {
  std::vector<Gid> out;
  for (std::uint32_t i = 0; i < seq._length; ++i) {
    out.push_back(copy(seq._buffer[i]));
  }
  return out;
}

/// What `ros2 node info` and `ros2 topic info --verbose` show of an endpoint: its topic, its
/// type, its QoS (reliability, durability, history depth) and its type hash.
std::string shown(const dds_builtintopic_endpoint_t& e) {
  dds_reliability_kind_t reliability{};
  dds_duration_t blocking = 0;
  dds_durability_kind_t durability{};
  dds_history_kind_t history{};
  std::int32_t depth = 0;
  void* user_data = nullptr;
  std::size_t size = 0;
  std::string text = std::string(e.topic_name) + " " + e.type_name;
  if (dds_qget_reliability(e.qos, &reliability, &blocking)) {
    text += reliability == DDS_RELIABILITY_RELIABLE ? " reliable" : " best_effort";
  }
  if (dds_qget_durability(e.qos, &durability)) {
    text += durability == DDS_DURABILITY_TRANSIENT_LOCAL ? " transient_local" : " volatile";
  }
  if (dds_qget_history(e.qos, &history, &depth)) {
    text += history == DDS_HISTORY_KEEP_LAST ? " keep_last " + std::to_string(depth) : " keep_all";
  }
  if (dds_qget_userdata(e.qos, &user_data, &size) && size > 0) {
    text += " " + std::string(static_cast<const char*>(user_data), size).substr(0, 16);
    dds_free(user_data);
  }
  return text;
}

/// shown() of every endpoint `builtin` (DCPSPublication or DCPSSubscription) discovered, by its
/// GID; within 5 s, until `wanted` of them are known.
std::map<Gid, std::string> endpoints(dds_entity_t tool, dds_entity_t builtin, std::size_t wanted) {
  const dds_entity_t reader = dds_create_reader(tool, builtin, nullptr, nullptr);
  std::map<Gid, std::string> found;
  const auto give_up = std::chrono::steady_clock::now() + 5s;
  while (found.size() < wanted && std::chrono::steady_clock::now() < give_up) {
    std::array<void*, 16> samples{};
    std::array<dds_sample_info_t, 16> infos{};
    const dds_return_t n = dds_take(reader, samples.data(), infos.data(), 16, 16);
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[static_cast<std::size_t>(i)].valid_data) {
        const auto* e =
            static_cast<const dds_builtintopic_endpoint_t*>(samples[static_cast<std::size_t>(i)]);
        found[padded(e->key)] = shown(*e);
      }
    }
    if (n > 0) {
      dds_return_loan(reader, samples.data(), n);
    }
    std::this_thread::sleep_for(20ms);
  }
  dds_delete(reader);
  return found;
}

TEST(DdsGraph, TheNodeIsAnnouncedWithTheGidsOfItsWritersAndReaders) {
  const std::uint32_t domain = test::use_loopback_dds();
  ros2types::Participant bridge(domain);
  const Endpoints ep(bridge, "/test/graph");
  const GraphAnnouncement node(bridge, ep, "/test/graph");

  ros2types::Participant tool(domain);  // started after the announcement: transient local
  const ros2types::Qos qos = ros2types::discovery_qos();
  const dds_entity_t info_reader =
      tool.reader(rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc,
                  std::string(ros2types::topic::kDiscoveryInfo), qos.get());
  std::optional<Announcement> heard;
  const auto give_up = std::chrono::steady_clock::now() + 5s;
  while (!heard && std::chrono::steady_clock::now() < give_up) {
    ros2types::take_each<rmw_dds_common_msg_dds__ParticipantEntitiesInfo_>(
        info_reader, [&](const rmw_dds_common_msg_dds__ParticipantEntitiesInfo_& m) {
          Announcement a{copy(m.gid_), {}};
          for (std::uint32_t i = 0; i < m.node_entities_info_seq_._length; ++i) {
            const auto& n = m.node_entities_info_seq_._buffer[i];
            a.nodes.push_back({n.node_namespace_, n.node_name_, gids(n.reader_gid_seq_),
                               gids(n.writer_gid_seq_)});
          }
          heard = a;
        });
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_TRUE(heard) << "nothing on ros_discovery_info within 5 s";
  EXPECT_EQ(heard->participant, copy(gid_of(bridge.handle())));
  ASSERT_EQ(heard->nodes.size(), 1U);
  const Node& n = heard->nodes.front();
  EXPECT_EQ(n.ns, "/test/graph");
  EXPECT_EQ(n.name, kNodeName);

  // What `ros2 node info /test/graph/hapticctrl_dds` lists: each GID is an endpoint DDS found,
  // on the node's topics.
  const std::map<Gid, std::string> publications =
      endpoints(tool.handle(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, 6);
  const std::map<Gid, std::string> subscriptions =
      endpoints(tool.handle(), DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION, 3);
  std::vector<std::string> published;
  for (const Gid& g : n.writers) {
    ASSERT_EQ(publications.count(g), 1U) << "a writer GID no publication has";
    published.push_back(publications.at(g));
  }
  // ROS 2's sensor-data profile on the five (best effort, volatile, keep last 5), its default on
  // the two command topics (reliable, volatile, keep last 10), and each type's hash (J6).
  const std::string sensor = " best_effort volatile keep_last 5 typehash=RIHS01_";
  EXPECT_EQ(
      published,
      (std::vector<std::string>{
          "rt/test/graph/handle_pose geometry_msgs::msg::dds_::PoseStamped_" + sensor,
          "rt/test/graph/rendered_wrench geometry_msgs::msg::dds_::WrenchStamped_" + sensor,
          "rt/test/graph/operator_wrench geometry_msgs::msg::dds_::WrenchStamped_" + sensor,
          "rt/test/graph/joint_states sensor_msgs::msg::dds_::JointState_" + sensor,
          "rt/test/graph/diagnostics diagnostic_msgs::msg::dds_::DiagnosticArray_" + sensor}));
  std::vector<std::string> subscribed;
  for (const Gid& g : n.readers) {
    ASSERT_EQ(subscriptions.count(g), 1U) << "a reader GID no subscription has";
    subscribed.push_back(subscriptions.at(g));
  }
  const std::string command = " reliable volatile keep_last 10 typehash=RIHS01_";
  EXPECT_EQ(subscribed,
            (std::vector<std::string>{
                "rt/test/graph/command std_msgs::msg::dds_::String_" + command,
                "rt/test/graph/operator_wrench_command geometry_msgs::msg::dds_::WrenchStamped_" +
                    command}));
}

}  // namespace
}  // namespace hapticctrl::dds_bridge
