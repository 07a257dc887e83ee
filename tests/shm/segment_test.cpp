// Tests of segment.hpp: creating (core) and attaching (everyone else) the shared-memory segment of
// one instance.
#include "hapticctrl/shm/segment.hpp"

#include <fcntl.h>
#include <grp.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <string>

#include "hapticctrl/shm/segment_handoff.hpp"
#include "support/child_process.hpp"
#include "support/segment_fixtures.hpp"

namespace hapticctrl::shm {
namespace {

using namespace std::chrono_literals;
using test::Child;
using test::ReadyPipe;
using test::unique_instance;

using test::exists;
using test::expect_shm_error;
using test::paths_of;
using test::RawHeader;
using test::RuntimeDirectory;

TEST(Segment, CreatedSegmentIsDescribedByItsHeader) {
  const std::string name = unique_instance("hdr");
  Segment core = Segment::create({.instance = name, .period_ns = 250'000});
  Segment reader = Segment::attach(name);
  const SegmentHeader& h = reader.header();
  EXPECT_EQ(h.magic.load(), kSegmentMagic);
  EXPECT_EQ(h.abi_version, kAbiVersion);
  EXPECT_EQ(h.segment_size, kSegmentSize);
  EXPECT_EQ(h.creator_pid, getpid());
  EXPECT_EQ(h.generation, 1U);
  EXPECT_EQ(h.period_ns, 250'000);
  EXPECT_EQ(std::string(h.instance.data()), name);
}

TEST(Segment, OnlyTheCoresUserAndGroupMayReachTheSocket) {
  const std::string name = unique_instance("mode");
  Segment core = Segment::create({.instance = name});
  const InstancePaths paths = paths_of(name);
  struct stat st {};
  ASSERT_EQ(stat(paths.directory.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0750U) << "group may enter, nobody else; nobody else may write";
  ASSERT_EQ(stat(paths.socket.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 0777, 0660U);
  ASSERT_EQ(stat(paths.lock.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600U);
}

TEST(Segment, ConfiguredGroupOwnsTheSocket) {
  const group* g = getgrgid(getegid());
  ASSERT_NE(g, nullptr);
  const std::string name = unique_instance("grp");
  Segment core = Segment::create({.instance = name, .group = g->gr_name});
  struct stat st {};
  ASSERT_EQ(stat(paths_of(name).socket.c_str(), &st), 0);
  EXPECT_EQ(st.st_gid, getegid());
  const std::string failed = unique_instance("g2");
  expect_shm_error([&] { Segment::create({.instance = failed, .group = "no-such-group-x"}); },
                   ShmErrc::kSystem, "unknown group");
  EXPECT_FALSE(exists(paths_of(failed).socket)) << "a failed create leaves nothing behind";
  EXPECT_FALSE(exists(paths_of(failed).lock));
}

TEST(Segment, CloseRemovesEveryName) {
  const std::string name = unique_instance("close");
  {
    Segment core = Segment::create({.instance = name});
    EXPECT_TRUE(exists(paths_of(name).socket));
  }
  EXPECT_FALSE(exists(paths_of(name).socket));
  EXPECT_FALSE(exists(paths_of(name).lock));
}

TEST(Segment, PublishedDataReachesAnotherProcess) {
  const std::string name = unique_instance("pub");
  Segment core = Segment::create({.instance = name});
  VpPayload vp;
  vp.cycle = 42;
  vp.object_wrench[2] = -9.81;
  core.writable<RegionId::kVp>().publish(vp, 123);
  Child reader([&] {
    Segment seg = Segment::attach(name);
    VpPayload got;
    const ReadResult r = seg.region<RegionId::kVp>().read(got);
    return (r.ok() && got.cycle == 42 && got.object_wrench[2] == -9.81 && r.publish_time_ns == 123)
               ? 0
               : 1;
  });
  EXPECT_EQ(reader.wait(), 0);
}

TEST(Segment, BlockedReaderOnReadOnlyMappingIsWokenByPublish) {
  const std::string name = unique_instance("wake");
  Segment core = Segment::create({.instance = name});
  ReadyPipe ready;
  Child reader([&] {
    Segment seg = Segment::attach(name);
    const std::uint32_t seen = seg.region<RegionId::kVp>().sequence_word();
    ready.signal();
    return seg.region<RegionId::kVp>().wait_for_publish(seen, 10s) == WaitStatus::kPublished ? 0
                                                                                             : 1;
  });
  ASSERT_EQ(ready.wait(), 'r');
  std::this_thread::sleep_for(20ms);
  core.writable<RegionId::kVp>().publish(VpPayload{}, 1);
  EXPECT_EQ(reader.wait(5s), 0);
}

TEST(Segment, BadInstanceNamesAreRefused) {
  for (const std::string& bad :
       std::vector<std::string>{"", "a/b", "../x", "with space", std::string(33, 'a')}) {
    expect_shm_error([&] { Segment::attach(bad); }, ShmErrc::kBadInstanceName,
                     "invalid instance name");
  }
}

TEST(Segment, TryAttachWaitsOutOnlyAMissingController) {
  const std::string name = unique_instance("try");
  EXPECT_FALSE(Segment::try_attach(name).has_value());
  Segment core = Segment::create({.instance = name});
  EXPECT_TRUE(Segment::try_attach(name).has_value());
  EXPECT_THROW((void)Segment::try_attach("bad/name"), ShmError);
}

TEST(Segment, ReaderNoticesItsCoreStopped) {
  const std::string name = unique_instance("repl");
  ReadyPipe ready;
  ReadyPipe stop;
  Child core_process([&] {
    Segment core = Segment::create({.instance = name});
    ready.signal();
    return stop.wait() == 's' ? 0 : 1;
  });
  ASSERT_EQ(ready.wait(), 'r');
  Segment reader = Segment::attach(name);
  EXPECT_TRUE(reader.still_current());
  EXPECT_TRUE(reader.core_alive());
  stop.signal('s');
  ASSERT_EQ(core_process.wait(), 0);
  EXPECT_FALSE(reader.still_current());
  EXPECT_FALSE(reader.core_alive());
  // A new core of the instance has a segment of its own.
  Segment next = Segment::create({.instance = name});
  EXPECT_FALSE(reader.still_current());
  EXPECT_TRUE(Segment::attach(name).still_current());
}

TEST(Segment, AbiMismatchNamesBothVersions) {
  const std::string name = unique_instance("abi");
  Segment core = Segment::create({.instance = name});
  {
    RawHeader raw(name);
    raw->abi_version = kAbiVersion + 1;
  }
  expect_shm_error([&] { Segment::attach(name); }, ShmErrc::kAbiMismatch,
                   "uses shared-memory ABI v" + std::to_string(kAbiVersion + 1) +
                       ", this program v" + std::to_string(kAbiVersion));
}

TEST(Segment, LayoutMismatchIsRefused) {
  const std::string name = unique_instance("lay");
  Segment core = Segment::create({.instance = name});
  {
    RawHeader raw(name);
    raw->regions[2].size += 8;
  }
  expect_shm_error([&] { Segment::attach(name); }, ShmErrc::kLayoutMismatch, "layout mismatch");
}

TEST(Segment, ARuntimeDirectoryOthersMayWriteIsRefused) {
  const RuntimeDirectory directory("/tmp/hapticctrl-test-" + std::to_string(getpid()) + "-open");
  const std::string name = unique_instance("world");
  Segment core = Segment::create({.instance = name});
  ASSERT_EQ(chmod(directory.path().c_str(), 0770), 0);
  expect_shm_error([&] { Segment::attach(name); }, ShmErrc::kInsecure,
                   "may be written by its group or by others");
  ASSERT_EQ(chmod(directory.path().c_str(), 0750), 0);
  EXPECT_NO_THROW(Segment::attach(name));
}

TEST(Segment, SecondLiveWriterOfARegionIsRefusedAndDeadOneTakenOver) {
  const std::string name = unique_instance("claim");
  Segment core = Segment::create({.instance = name});
  ReadyPipe ready;
  Child first_writer([&] {
    Segment seg = Segment::attach(name, {.write = {RegionId::kForce}});
    seg.writable<RegionId::kForce>().publish(ForcePayload{}, 1);
    ready.signal();
    pause();
    return 0;
  });
  ASSERT_EQ(ready.wait(), 'r');
  expect_shm_error([&] { Segment::attach(name, {.write = {RegionId::kForce}}); },
                   ShmErrc::kWriterConflict,
                   "already written by live process " + std::to_string(first_writer.pid()));
  first_writer.kill_now();
  ASSERT_EQ(first_writer.wait(), 128 + SIGKILL);
  Segment second = Segment::attach(name, {.write = {RegionId::kForce}});
  EXPECT_NO_THROW((void)second.writable<RegionId::kForce>());
  ASSERT_TRUE(second.writer_of(RegionId::kForce).has_value());
  EXPECT_EQ(second.writer_of(RegionId::kForce)->pid, getpid());
}

TEST(Segment, CoreRegionsCannotBeClaimedByOthers) {
  const std::string name = unique_instance("corew");
  Segment core = Segment::create({.instance = name});
  Child other([&] {
    try {
      Segment::attach(name, {.write = {RegionId::kVp}});
    } catch (const ShmError& e) {
      // The region as a value (callers decide on it, hmi's operator), and in the text.
      return e.code() == ShmErrc::kWriterConflict && e.region() == RegionId::kVp &&
                     std::strstr(e.what(), "region VP") != nullptr
                 ? 0
                 : 2;
    }
    return 1;
  });
  EXPECT_EQ(other.wait(), 0);
}

TEST(Segment, WritableAccessWithoutClaimIsALogicError) {
  const std::string name = unique_instance("nowr");
  Segment core = Segment::create({.instance = name});
  Segment reader = Segment::attach(name);
  EXPECT_THROW((void)reader.writable<RegionId::kVpr>(), std::logic_error);
  EXPECT_THROW((void)reader.ctrl_writer(), std::logic_error);
  EXPECT_THROW((void)reader.ctrl_reader(), std::logic_error);
  EXPECT_THROW((void)reader.header_for_writing(), std::logic_error);
}

TEST(Segment, ReadOnlyRegionsAreMappedReadOnly) {
  const std::string name = unique_instance("ro");
  Segment core = Segment::create({.instance = name});
  Child reader([&] {
    struct sigaction on_segv {};
    on_segv.sa_handler = [](int) { _exit(42); };
    sigaction(SIGSEGV, &on_segv, nullptr);
    Segment seg = Segment::attach(name);
    auto& vp = const_cast<RegionType<RegionId::kVp>&>(seg.region<RegionId::kVp>());
    vp.raw_sequence_word().store(1);  // must fault
    return 0;
  });
  EXPECT_EQ(reader.wait(), 42);
}

TEST(Segment, CtrlCommandsFromAnotherProcessArriveInOrder) {
  const std::string name = unique_instance("ctrl");
  Segment core = Segment::create({.instance = name});
  Child hmi([&] {
    Segment seg = Segment::attach(name, {.ctrl_writer = true});
    CtrlWriter& w = seg.ctrl_writer();
    w.send(CtrlCode::kPowerOn, 0, 0);
    w.send(CtrlCode::kEmergencyStop, 0, 0);
    std::uint64_t last = 0;
    w.send(CtrlCode::kEmergencyReset, 0, 0, &last);
    for (int i = 0; i < 5000 && !w.consumed(last); ++i) {
      std::this_thread::sleep_for(1ms);
    }
    return w.consumed(last) ? 0 : 1;
  });
  std::vector<CtrlCode> codes;
  CtrlReader reader = core.ctrl_reader();
  for (int i = 0; i < 5000 && codes.size() < 3; ++i) {
    reader.drain([&](const CtrlCommand& c) {
      codes.push_back(c.code);
      return true;
    });
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(hmi.wait(), 0);
  EXPECT_EQ(codes, (std::vector<CtrlCode>{CtrlCode::kPowerOn, CtrlCode::kEmergencyStop,
                                          CtrlCode::kEmergencyReset}));
}

TEST(Segment, CtrlSlotsAreClaimedPerProcess) {
  const std::string name = unique_instance("slots");
  Segment core = Segment::create({.instance = name});
  Segment a = Segment::attach(name, {.ctrl_writer = true});
  Segment b = Segment::attach(name, {.ctrl_writer = true});
  // Same process: a and b share our identity, so they may share a slot; what matters is that a
  // dead process's slot is reusable and a full table is reported.
  EXPECT_LT(a.ctrl_writer().slot_index(), kCtrlSlots);
  EXPECT_LT(b.ctrl_writer().slot_index(), kCtrlSlots);
}

}  // namespace
}  // namespace hapticctrl::shm
