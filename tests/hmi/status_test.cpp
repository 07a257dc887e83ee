// Tests of status.hpp: what the operator panel shows, read from an instance's regions in one go,
// and its JSON form (`hapticctrl-hmi status --json`).
#include "hapticctrl/hmi/status.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace hapticctrl::hmi {
namespace {

ControllerStatus connected(std::uint64_t cycle, std::uint64_t control_frames) {
  ControllerStatus s;
  s.instance = "lab";
  s.vp_ok = true;
  s.link_ok = true;
  s.vpr_ok = true;
  s.vp.cycle = cycle;
  s.link.session_id = 7;
  s.link.peer_ipv4 = 0x7f000001;
  s.link.peer_port = 40000;
  s.link.control_accepted = control_frames;
  s.vpr.session_id = 7;
  s.read_at = TimePoint{std::chrono::milliseconds(5)};
  s.vpr.received_time_ns = 4'000'000;
  return s;
}

TEST(Status, FramesPerCycleIsTheControllersViewOfTheClientStream) {
  EXPECT_DOUBLE_EQ(control_frames_per_cycle(connected(1000, 990), connected(2000, 1980)), 0.99);
  ControllerStatus other = connected(2000, 1980);
  other.link.session_id = 8;
  EXPECT_LT(control_frames_per_cycle(connected(1000, 990), other), 0.0) << "another session";
  EXPECT_LT(control_frames_per_cycle(connected(1000, 990), connected(1000, 990)), 0.0);
  EXPECT_LT(control_frames_per_cycle(ControllerStatus{}, connected(10, 1)), 0.0);
}

TEST(Status, ClientSampleAgeNeedsASession) {
  EXPECT_DOUBLE_EQ(connected(1, 1).client_age_ms(), 1.0);
  EXPECT_LT(ControllerStatus{}.client_age_ms(), 0.0);
}

TEST(Status, JsonCarriesStateWrenchesHealthAndLink) {
  ControllerStatus s = connected(42, 40);
  s.vp.state_word = shm::state_bits::kPowered | shm::state_bits::kCoupled;
  s.vp.core_state = static_cast<std::uint32_t>(shm::CoreState::kRunning);
  s.position.operator_wrench = {5, 0, 0, 0, 0, 0};
  s.telemetry.rt_mode = static_cast<std::uint32_t>(shm::RtMode::kFifoLocked);
  s.telemetry.wake_latency.p99_ns = 12'000;
  s.link.dropped[0] = 2;
  s.link.dropped[3] = 1;
  const std::string json = status_json(s);
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');
  for (const char* part :
       {"\"instance\":\"lab\"", "\"cycle\":42", "\"core_state\":\"running\"", "\"powered\":true",
        "\"emergency_stop\":false", "\"coupled\":true", "\"operator_wrench\":[5,0,0,0,0,0]",
        "\"rt_mode\":\"SCHED_FIFO+mlockall\"", "\"wake_p99_ns\":12000", "\"connected\":true",
        "\"peer\":\"127.0.0.1:40000\"", "\"sample_age_ms\":1", "\"frames_dropped\":3"}) {
    EXPECT_NE(json.find(part), std::string::npos) << part << " in " << json;
  }
  EXPECT_NE(status_json(ControllerStatus{}).find("\"connected\":false"), std::string::npos);
  EXPECT_NE(json.find("\"awaiting_operator\":false"), std::string::npos);
  s.vp.state_word |= shm::state_bits::kAwaitingOperator;
  EXPECT_NE(status_json(s).find("\"awaiting_operator\":true"), std::string::npos)
      << "restarted after a fault: waiting for the operator's power-on";
}

TEST(Status, JsonCarriesEveryRegionThroughItsFieldTable) {
  ControllerStatus s = connected(42, 40);
  s.position_ok = true;
  s.telemetry_ok = true;
  s.telemetry.wake_histogram[2] = 9;
  s.vpr.contacts[0].stiffness = 3000;
  const std::string json = status_json(s);
  for (const char* part :
       {",\"regions\":{\"position\":{\"cycle\":", "\"vp\":{\"cycle\":42,",
        "\"vpr\":{\"session_id\":", "\"wake_histogram\":[0,0,9,",
        "\"contacts\":[{\"point\":[0,0,0],", "\"peer_ipv4\":\"127.0.0.1\",\"peer_port\":40000",
        "\"stiffness\":3000,"}) {
    EXPECT_NE(json.find(part), std::string::npos) << part << " in " << json;
  }
  s.telemetry_ok = false;
  EXPECT_NE(status_json(s).find("\"telemetry\":null"), std::string::npos);
}

TEST(Status, JsonSaysNullForWhatIsNotANumber) {
  // "-nan" made the document unreadable for every reader (2026-12-03); 0 would hide the fault.
  ControllerStatus s = connected(42, 40);
  s.vp.channel_energy_out = std::numeric_limits<double>::quiet_NaN();
  s.vp.object_wrench[2] = std::numeric_limits<double>::infinity();
  const std::string json = status_json(s);
  EXPECT_NE(json.find("\"channel_energy_out\":null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"object_wrench\":[0,0,null,0,0,0]"), std::string::npos) << json;
  EXPECT_EQ(json.find("nan"), std::string::npos) << json;
  EXPECT_EQ(json.find("inf"), std::string::npos) << json;
}

}  // namespace
}  // namespace hapticctrl::hmi
