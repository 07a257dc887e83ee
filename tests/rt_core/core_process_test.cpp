// The real hapticctrl-core binary, driven through shared memory like the other processes do.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

#include "hapticctrl/shm/rendezvous.hpp"
#include "hapticctrl/shm/segment.hpp"
#include "support/child_process.hpp"
#include "support/spawned_process.hpp"
#include "support/temp_directory.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::SpawnedProcess;

bool segment_exists(const std::string& instance) {
  struct stat st {};
  const shm::InstancePaths paths =
      shm::InstancePaths::in(shm::creator_runtime_directory(), instance);
  return stat(paths.socket.c_str(), &st) == 0 || stat(paths.lock.c_str(), &st) == 0;
}

/// Attaches as soon as the core is up (bounded).
std::optional<shm::Segment> attach_when_ready(const std::string& instance, bool ctrl_writer) {
  for (int i = 0; i < 1000; ++i) {
    try {
      return shm::Segment::attach(instance, {.ctrl_writer = ctrl_writer});
    } catch (const shm::ShmError&) {
      std::this_thread::sleep_for(5ms);
    }
  }
  return std::nullopt;
}

/// Reads VP until `predicate` holds (bounded by `timeout`); returns the matching sample.
template <typename Predicate>
std::optional<shm::VpPayload> wait_vp(const shm::Segment& seg, Predicate predicate,
                                      std::chrono::milliseconds timeout = 5s) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  const auto& vp_cell = seg.region<shm::RegionId::kVp>();
  while (std::chrono::steady_clock::now() < deadline) {
    const std::uint32_t seen = vp_cell.sequence_word();
    shm::VpPayload vp;
    if (vp_cell.read(vp).ok() && predicate(vp)) {
      return vp;
    }
    vp_cell.wait_for_publish(seen, 20ms);
  }
  return std::nullopt;
}

std::vector<std::string> core_args(const std::string& instance,
                                   std::vector<std::string> extra = {}) {
  // A 10 ms period: these tests are about behaviour, not timing, and run beside others (and
  // under sanitizers), where a 2 ms period could miss 5 deadlines in a row by load alone.
  std::vector<std::string> args{"--instance", instance, "--period-us", "10000", "--rt", "ignore"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

TEST(CoreProcess, InjectedOverrunTripsFailSafeInOrderAndExitsWithTheReason) {
  const std::string instance = test::unique_instance("fs");
  const test::TempDirectory boxes("boxes");
  SpawnedProcess core(HAPTICCTRL_CORE_BINARY, core_args(instance, {"--allow-fault-injection",
                                                                   "--state-dir", boxes.path()}));
  auto seg = attach_when_ready(instance, true);
  ASSERT_TRUE(seg.has_value()) << core.err();
  seg->ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);
  const auto powered = wait_vp(*seg, [](const shm::VpPayload& vp) {
    return (vp.state_word & shm::state_bits::kPowered) != 0;
  });
  ASSERT_TRUE(powered.has_value()) << "power-on through ctrl";
  EXPECT_EQ(powered->core_state, static_cast<std::uint32_t>(shm::CoreState::kRunning));

  seg->ctrl_writer().send(shm::CtrlCode::kInjectOverrun, 5, 0);
  const auto closed = wait_vp(*seg, [](const shm::VpPayload& vp) {
    return vp.core_state == static_cast<std::uint32_t>(shm::CoreState::kFailSafe);
  });
  ASSERT_TRUE(closed.has_value()) << core.err();
  // Steps 1 and 2 (inhibit, power off) precede step 3: the closing VP is already unpowered.
  EXPECT_EQ(closed->state_word & shm::state_bits::kPowered, 0U);
  EXPECT_NE(closed->state_word & shm::state_bits::kFailSafe, 0U);
  EXPECT_EQ(closed->stop_reason, static_cast<std::uint32_t>(shm::StopReason::kConsecutiveMisses));
  EXPECT_TRUE(closed->object_wrench == shm::Vector6{});

  shm::TelemetryPayload t;
  ASSERT_TRUE(seg->region<shm::RegionId::kTelemetry>().read(t).ok()) << "published before VP";
  EXPECT_EQ(t.core_state, static_cast<std::uint32_t>(shm::CoreState::kFailSafe));
  EXPECT_GE(t.misses_total, 5U);

  EXPECT_EQ(core.wait(), 3);
  const std::string err = core.err();
  EXPECT_NE(err.find("FAIL-SAFE"), std::string::npos) << err;
  EXPECT_NE(err.find("5 consecutive deadline misses"), std::string::npos) << err;
  EXPECT_EQ(err.find("stall of the machine"), std::string::npos)
      << "an overrun of the software is not called a stall of the machine: " << err;
  const auto bb = err.find("black box: ");
  ASSERT_NE(bb, std::string::npos) << err;
  const std::string bb_path = err.substr(bb + 11, err.find('\n', bb) - bb - 11);
  EXPECT_EQ(bb_path, boxes / ("hapticctrl-blackbox-" + instance + "." + std::to_string(core.pid()) +
                              ".csv"));
  struct stat st {};
  ASSERT_EQ(lstat(bb_path.c_str(), &st), 0) << bb_path;
  EXPECT_TRUE(S_ISREG(st.st_mode));
  EXPECT_EQ(st.st_mode & 07777, 0600U) << "only the controller's user reads its black box";
  seg.reset();
  EXPECT_FALSE(segment_exists(instance)) << "regions released";
}

/// The fields of the last line of a CSV file.
std::vector<std::string> last_csv_record(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (!line.empty()) {
      last = line;
    }
  }
  std::vector<std::string> fields;
  std::istringstream split(last);
  for (std::string field; std::getline(split, field, ',');) {
    fields.push_back(field);
  }
  return fields;
}

/// A file removed when the test's scope ends (after the processes declared after it).
struct RemovedAtEnd {
  std::string path;
  explicit RemovedAtEnd(std::string p) : path(std::move(p)) {}
  ~RemovedAtEnd() { std::remove(path.c_str()); }
  RemovedAtEnd(const RemovedAtEnd&) = delete;
  RemovedAtEnd& operator=(const RemovedAtEnd&) = delete;
};

TEST(CoreProcess, AFiftyMillisecondSigstopLeavesABlackBoxThatEndsWithTheStall) {
  // H5: a fail-safe caused by a stall (a late wake-up skipping slots) used to leave a black box
  // that ended with a normal cycle. 50 ms at a 5 ms period: 10 slots.
  for (int attempt = 0; attempt < 3; ++attempt) {
    const std::string instance = test::unique_instance("sigstop");
    // The core fails safe here on purpose, so it leaves its restart marker: removed after it.
    const RemovedAtEnd marker(shm::creator_runtime_directory() + "/hapticctrl-running." + instance);
    SpawnedProcess core(HAPTICCTRL_CORE_BINARY,
                        {"--instance", instance, "--period-us", "5000", "--rt", "ignore"});
    ASSERT_TRUE(attach_when_ready(instance, false).has_value()) << core.err();
    std::this_thread::sleep_for(200ms);
    if (core.wait(0ms) != -1) {
      continue;  // it failed safe on a stall of this VM's own before ours: try again
    }
    core.signal(SIGSTOP);
    std::this_thread::sleep_for(50ms);
    core.signal(SIGCONT);
    ASSERT_EQ(core.wait(), 3) << core.err();
    const std::string err = core.err();
    EXPECT_NE(err.find("on a stall of the machine (the clock woke "), std::string::npos)
        << "said, for scripts/run.sh: " << err;
    const auto bb = err.find("black box: ");
    ASSERT_NE(bb, std::string::npos) << err;
    const std::string bb_path = err.substr(bb + 11, err.find('\n', bb) - bb - 11);
    EXPECT_EQ(bb_path.rfind(shm::creator_runtime_directory() + "/", 0), 0U)
        << "by default in the instance's runtime directory, never /tmp: " << bb_path;
    const std::vector<std::string> last = last_csv_record(bb_path);
    std::remove(bb_path.c_str());
    // cycle,scheduled_ns,wake_latency_ns,servo_start_delay_ns,servo_execution_ns,miss,degraded,
    // stall,skipped,...
    ASSERT_GT(last.size(), 8U);
    EXPECT_EQ(last[7], "1") << "the last record is the stall";
    EXPECT_GE(std::stoll(last[2]), 45'000'000LL) << "woken about 50 ms late";
    EXPECT_GE(std::stoll(last[8]), 8) << "slots skipped";
    return;
  }
  FAIL() << "the core failed safe on its own in 3 attempts";
}

TEST(CoreProcess, ABlackBoxDirectoryOthersMayWriteIsRefusedAtStart) {
  // A root core wrote its black box into /tmp through a link planted there (J4 review): a
  // directory that others may write is refused before the run, with the reason.
  const std::string instance = test::unique_instance("bbdir");
  SpawnedProcess core(HAPTICCTRL_CORE_BINARY, core_args(instance, {"--state-dir", "/tmp"}));
  EXPECT_EQ(core.wait(), 1);
  EXPECT_NE(core.err().find("/tmp may be written by its group or by others"), std::string::npos)
      << core.err();
  EXPECT_FALSE(segment_exists(instance));
}

TEST(CoreProcess, ALatchedEmergencyStopOutlivesAKilledCoreUntilAReset) {
  // ISO 13850 / IEC 60204-1: the stop stays latched until a deliberate reset. A restarted core
  // accepted power-on with no reset (9 of 9, J4 review of f3c5aec).
  const std::string instance = test::unique_instance("latch");
  const test::TempDirectory state("state");
  const std::string latch = state / ("hapticctrl-estop." + instance);
  const auto args = core_args(instance, {"--state-dir", state.path()});
  {
    SpawnedProcess core(HAPTICCTRL_CORE_BINARY, args);
    auto seg = attach_when_ready(instance, true);
    ASSERT_TRUE(seg.has_value()) << core.err();
    seg->ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);
    ASSERT_TRUE(wait_vp(*seg, [](const shm::VpPayload& vp) {
      return (vp.state_word & shm::state_bits::kPowered) != 0;
    }));
    seg->ctrl_writer().send(shm::CtrlCode::kEmergencyStop, 0, 0);
    ASSERT_TRUE(wait_vp(*seg, [](const shm::VpPayload& vp) {
      return (vp.state_word & shm::state_bits::kEmergencyStop) != 0;
    }));
    bool kept = false;
    for (int i = 0; i < 200 && !kept; ++i) {  // the keeper polls every 2 ms
      kept = access(latch.c_str(), F_OK) == 0;
      std::this_thread::sleep_for(5ms);
    }
    ASSERT_TRUE(kept) << "the latch never reached its file";
    core.signal(SIGKILL);
    EXPECT_EQ(core.wait(), 128 + SIGKILL);
  }
  SpawnedProcess next(HAPTICCTRL_CORE_BINARY, args);
  auto seg = attach_when_ready(instance, true);
  ASSERT_TRUE(seg.has_value()) << next.err();
  ASSERT_TRUE(wait_vp(*seg, [](const shm::VpPayload& vp) {
    return (vp.state_word & shm::state_bits::kEmergencyStop) != 0;
  })) << "the next core starts with the stop latched";
  EXPECT_NE(next.err().find("the emergency stop is still latched (latched at "), std::string::npos)
      << next.err();
  seg->ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);
  EXPECT_FALSE(wait_vp(
      *seg,
      [](const shm::VpPayload& vp) { return (vp.state_word & shm::state_bits::kPowered) != 0; },
      500ms))
      << "power-on refused while latched";
  seg->ctrl_writer().send(shm::CtrlCode::kEmergencyReset, 0, 0);
  ASSERT_TRUE(wait_vp(*seg, [](const shm::VpPayload& vp) {
    return (vp.state_word & shm::state_bits::kEmergencyStop) == 0;
  }));
  bool removed = false;
  for (int i = 0; i < 200 && !removed; ++i) {
    removed = access(latch.c_str(), F_OK) != 0;
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_TRUE(removed) << "a reset removes the latch";
  seg->ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);
  EXPECT_TRUE(wait_vp(*seg, [](const shm::VpPayload& vp) {
    return (vp.state_word & shm::state_bits::kPowered) != 0;
  })) << "after the reset, power-on works";
  seg.reset();
  next.signal(SIGTERM);
  EXPECT_EQ(next.wait(), 0) << next.err();
}

TEST(CoreProcess, AfterAKilledCoreOnlyAnOperatorPowersTheNextOneOn) {
  // J8 / IEC 60204-1 7.5: a controller restarted after a fault does not start by itself: `R` in
  // the panel, then the demo powered the new controller on 18 cycles later (J8 review). After an
  // orderly stop nothing is awaited.
  const std::string instance = test::unique_instance("restart");
  const test::TempDirectory state("state");
  const auto args = core_args(instance, {"--state-dir", state.path()});
  const auto powered = [](const shm::VpPayload& vp) {
    return (vp.state_word & shm::state_bits::kPowered) != 0;
  };
  const auto awaiting = [](const shm::VpPayload& vp) {
    return (vp.state_word & shm::state_bits::kAwaitingOperator) != 0;
  };
  {
    SpawnedProcess core(HAPTICCTRL_CORE_BINARY, args);
    auto seg = attach_when_ready(instance, true);
    ASSERT_TRUE(seg.has_value()) << core.err();
    ASSERT_TRUE(wait_vp(*seg, [&](const shm::VpPayload& vp) { return !awaiting(vp); }));
    seg->ctrl_writer().send(shm::CtrlCode::kPowerOn, shm::kPowerOnByClient, 0);
    ASSERT_TRUE(wait_vp(*seg, powered)) << "a first start: a client powers on";
    seg.reset();
    core.signal(SIGKILL);
    EXPECT_EQ(core.wait(), 128 + SIGKILL);
  }
  SpawnedProcess next(HAPTICCTRL_CORE_BINARY, args);
  auto seg = attach_when_ready(instance, true);
  ASSERT_TRUE(seg.has_value()) << next.err();
  ASSERT_TRUE(wait_vp(*seg, awaiting)) << "the next core awaits an operator";
  EXPECT_NE(next.err().find("did not stop in order (running since "), std::string::npos)
      << next.err();
  seg->ctrl_writer().send(shm::CtrlCode::kPowerOn, shm::kPowerOnByClient, 0);
  EXPECT_FALSE(wait_vp(*seg, powered, 500ms)) << "a client's power-on is refused";
  seg->ctrl_writer().send(shm::CtrlCode::kPowerOn, shm::kPowerOnByOperator, 0);
  EXPECT_TRUE(wait_vp(*seg, [&](const shm::VpPayload& vp) { return powered(vp) && !awaiting(vp); }))
      << "the operator's power-on is the acknowledgement";
  seg.reset();
  next.signal(SIGTERM);
  EXPECT_EQ(next.wait(), 0) << next.err();
  SpawnedProcess third(HAPTICCTRL_CORE_BINARY, args);
  seg = attach_when_ready(instance, true);
  ASSERT_TRUE(seg.has_value()) << third.err();
  ASSERT_TRUE(wait_vp(*seg, [&](const shm::VpPayload& vp) { return !awaiting(vp); }))
      << "after an orderly stop nothing is awaited";
  EXPECT_EQ(third.err().find("did not stop in order"), std::string::npos) << third.err();
  seg.reset();
  third.signal(SIGTERM);
  EXPECT_EQ(third.wait(), 0) << third.err();
}

TEST(CoreProcess, StopRequestExitsZeroAndLeavesNoSegment) {
  const std::string instance = test::unique_instance("stop");
  SpawnedProcess core(HAPTICCTRL_CORE_BINARY, core_args(instance));
  auto seg = attach_when_ready(instance, true);
  ASSERT_TRUE(seg.has_value()) << core.err();
  seg->ctrl_writer().send(shm::CtrlCode::kStop, 0, 0);
  const auto stopping = wait_vp(*seg, [](const shm::VpPayload& vp) {
    return vp.core_state == static_cast<std::uint32_t>(shm::CoreState::kStopping);
  });
  ASSERT_TRUE(stopping.has_value());
  EXPECT_EQ(stopping->stop_reason, static_cast<std::uint32_t>(shm::StopReason::kStopRequested));
  EXPECT_EQ(core.wait(), 0) << core.err();
  EXPECT_NE(core.err().find("stop requested"), std::string::npos);
  seg.reset();
  EXPECT_FALSE(segment_exists(instance));
}

TEST(CoreProcess, SigtermStopsCleanly) {
  const std::string instance = test::unique_instance("term");
  SpawnedProcess core(HAPTICCTRL_CORE_BINARY, core_args(instance));
  ASSERT_TRUE(attach_when_ready(instance, false).has_value()) << core.err();
  core.signal(SIGTERM);
  EXPECT_EQ(core.wait(), 0) << core.err();
  EXPECT_NE(core.err().find("stopped by signal"), std::string::npos);
  EXPECT_FALSE(segment_exists(instance));
}

TEST(CoreProcess, SecondCoreWithTheSameInstanceIsRefused) {
  const std::string instance = test::unique_instance("dup");
  SpawnedProcess first(HAPTICCTRL_CORE_BINARY, core_args(instance));
  ASSERT_TRUE(attach_when_ready(instance, false).has_value()) << first.err();
  SpawnedProcess second(HAPTICCTRL_CORE_BINARY, core_args(instance));
  EXPECT_EQ(second.wait(), 1);
  EXPECT_NE(second.err().find("already running (core pid " + std::to_string(first.pid())),
            std::string::npos)
      << second.err();
  first.signal(SIGINT);
  EXPECT_EQ(first.wait(), 0);
}

TEST(CoreProcess, DurationAndJsonReportTheFigures) {
  const std::string instance = test::unique_instance("json");
  SpawnedProcess core(HAPTICCTRL_CORE_BINARY, core_args(instance, {"--duration", "0.3", "--json"}));
  EXPECT_EQ(core.wait(), 0) << core.err();
  const std::string out = core.out();
  EXPECT_NE(out.find("\"stop_reason\":\"duration elapsed\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"wake_latency\":{"), std::string::npos);
  EXPECT_FALSE(segment_exists(instance));
}

TEST(CoreProcess, BadArgumentsAreExplained) {
  SpawnedProcess core(HAPTICCTRL_CORE_BINARY, {"--period-us", "5"});
  EXPECT_EQ(core.wait(), 64);
  EXPECT_NE(core.err().find("--period-us: expected a number from 100 to 10000, got '5'"),
            std::string::npos)
      << core.err();
}

TEST(CoreProcess, AnImpossibleCpuAHistogramItCannotWriteAndNaNAreRefusedBeforeAnyRun) {
  // H3: each used to be accepted (a NaN duration ran, CPU 64 was logged as pinned, the
  // histogram was lost at the end without a word).
  const std::string instance = test::unique_instance("refuse");
  SpawnedProcess cpu(HAPTICCTRL_CORE_BINARY, core_args(instance, {"--cpu", "64"}));
  EXPECT_EQ(cpu.wait(), 64);
  EXPECT_NE(cpu.err().find("--cpu 64: this machine has"), std::string::npos) << cpu.err();
  SpawnedProcess nan(HAPTICCTRL_CORE_BINARY, core_args(instance, {"--duration", "nan"}));
  EXPECT_EQ(nan.wait(), 64);
  EXPECT_NE(nan.err().find("--duration: expected a number from 0 to 1e+07, got 'nan'"),
            std::string::npos)
      << nan.err();
  SpawnedProcess histogram(HAPTICCTRL_CORE_BINARY,
                           core_args(instance, {"--histogram", "/nonexistent-dir/h.txt"}));
  EXPECT_EQ(histogram.wait(), 1);
  EXPECT_NE(histogram.err().find("cannot write the histogram '/nonexistent-dir/h.txt'"),
            std::string::npos)
      << histogram.err();
  EXPECT_FALSE(segment_exists(instance));
}

TEST(CoreProcess, AModelThatCannotCarryItsOwnWeightIsRefused) {
  // H3: valid line by line, but joint 2 could not hold the arm up at 0.2 N.m.
  std::ifstream shipped(HAPTICCTRL_SHIPPED_ARM_MODEL);
  std::stringstream text;
  text << shipped.rdbuf();
  std::string model = text.str();
  const auto joint2 = model.find("[joint 2]");
  for (const std::string key : {"torque_peak = ", "torque_continuous = "}) {
    const auto at = model.find(key, joint2);
    model.replace(at, model.find('\n', at) - at, key + "0.2");
  }
  const std::string path = "/tmp/hapticctrl-weak-" + std::to_string(getpid()) + ".arm";
  std::ofstream(path) << model;
  const std::string instance = test::unique_instance("weak");
  SpawnedProcess core(HAPTICCTRL_CORE_BINARY, core_args(instance, {"--model", path}));
  EXPECT_EQ(core.wait(), 1);
  EXPECT_NE(core.err().find("of joint 2's peak torque at some pose: it cannot be gravity-"),
            std::string::npos)
      << core.err();
  EXPECT_FALSE(segment_exists(instance));
  std::remove(path.c_str());
}

}  // namespace
}  // namespace hapticctrl
