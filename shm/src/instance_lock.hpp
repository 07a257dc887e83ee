#pragma once
// The instance lock (instance_lock.cpp): internal to shm/, setup code only.
#include <cstdint>
#include <string>

#include "hapticctrl/shm/rendezvous.hpp"

namespace hapticctrl::shm {

/// What the lock file says about the last core that held it: "pid generation".
struct LockRecord {
  long pid = 0;
  std::uint64_t generation = 0;
};

LockRecord read_lock_record(int fd);
/// Throws ShmError on failure.
void write_lock_record(int fd, const LockRecord& record);

/// Takes the exclusive flock that marks the live core of an instance and returns its
/// descriptor. An orderly stop removes the lock file while still holding it, so the lock taken
/// must still be the file the name points to (else a core that stopped meanwhile removed it: try
/// again). A core that died leaves the file, with its "pid generation", for the next one. Throws
/// ShmError(kAlreadyRunning) naming the live core's pid.
int acquire_instance_lock(const InstancePaths& paths, const std::string& instance);

}  // namespace hapticctrl::shm
