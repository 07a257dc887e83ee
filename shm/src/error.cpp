// Implements error.hpp: the one exception of the shm layer's setup code (creating, finding and
// attaching segments).
#include "hapticctrl/shm/error.hpp"

#include <grp.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace hapticctrl::shm {

void throw_system_error(const std::string& what, int error) {
  if (error == EACCES || error == EPERM) {
    throw ShmError(ShmErrc::kPermissionDenied,
                   what +
                       ": permission denied (run as the controller's user or a member of its "
                       "group, see docs/security.md; a controller of your own: set "
                       "HAPTICCTRL_RUNTIME_DIR to a directory of yours, e.g. "
                       "$XDG_RUNTIME_DIR/hapticctrl)");
  }
  throw ShmError(ShmErrc::kSystem, what + ": " + std::strerror(error));
}

unsigned group_id(const std::string& group) {
  if (group.empty()) {
    return getegid();
  }
  std::string buffer(16384, '\0');
  struct group entry {};
  struct group* result = nullptr;
  int rc = ERANGE;
  while (rc == ERANGE && buffer.size() <= (1U << 20)) {
    rc = getgrnam_r(group.c_str(), &entry, buffer.data(), buffer.size(), &result);
    if (rc == ERANGE) {
      buffer.resize(buffer.size() * 2);
    }
  }
  if (rc != 0 || result == nullptr) {
    throw ShmError(ShmErrc::kSystem, "unknown group '" + group + "' for the shared-memory segment");
  }
  return entry.gr_gid;
}

}  // namespace hapticctrl::shm
