// The C API's sessions, errors and diagnostics (virtuose_api.h); the other virtuose_*.cpp files
// hold its parameters, state, commands, loop, conversions and unavailable functions.
#include "hapticctrl/virtuose_api.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <new>

#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "virtuose_context.hpp"
#include "virtuose_reconnect.hpp"

using hapticctrl::client::ClientError;
using hapticctrl::client::Connection;
using hapticctrl::client::ErrorCode;
using hapticctrl::client::StateSnapshot;
using hapticctrl::client::virtuose::code_of;
using hapticctrl::client::virtuose::Context;
using hapticctrl::client::virtuose::context_of;
using hapticctrl::client::virtuose::error_of;
using hapticctrl::client::virtuose::fail;
using hapticctrl::client::virtuose::kFirstAnswerTimeout;
using hapticctrl::client::virtuose::Reconnector;

namespace {

/// The VirtuoseAPI level of virtuose_api.h.
constexpr int kApiMajor = 4;
constexpr int kApiMinor = 4;
/// The joints every answer carries.
constexpr int kAxes = 6;

}  // namespace

extern "C" {
// NOLINTBEGIN(readability-identifier-naming): VirtuoseAPI's names

VirtContext virtOpen(const char* nom) {
  if (nom == nullptr) {
    fail(nullptr, VIRT_E_WRONG_FORMAT, "virtOpen: NULL address");
    return nullptr;
  }
  try {
    auto vc = std::make_unique<Context>();
    vc->address = hapticctrl::client::Address::parse(nom);
    vc->set_link(std::make_shared<Connection>(vc->address));
    // As Haption's: returns once the controller's first answer is here, so that the getters
    // report the arm, never a default pose (they did, in 9 opens of 10).
    StateSnapshot first;
    if (!vc->link()->wait_for_answer(0, kFirstAnswerTimeout, first)) {
      fail(nullptr, VIRT_E_TIME_OUT,
           "virtOpen: the session opened, but no answer from the controller came within 2 s");
      return nullptr;
    }
    vc->reconnector = std::make_unique<Reconnector>(*vc);
    Context* handle = vc.get();
    hapticctrl::client::virtuose::register_context(std::move(vc));
    return handle;
  } catch (const ClientError& e) {
    fail(nullptr, e.code() == ErrorCode::kInvalidArgument ? VIRT_E_WRONG_FORMAT : code_of(e.code()),
         e.what());
  } catch (const std::bad_alloc&) {
    fail(nullptr, VIRT_E_OUT_OF_MEMORY, "virtOpen: out of memory");
  } catch (const std::exception& e) {
    fail(nullptr, VIRT_E_COMMUNICATION_FAILURE, e.what());
  }
  return nullptr;
}

int virtClose(VirtContext VC) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  vc->reconnector.reset();  // no next session from here on
  virtStopLoop(VC);
  const int rc = vc->guarded([&] { vc->link()->close(); });
  const std::unique_ptr<Context> closed = hapticctrl::client::virtuose::unregister_context(VC);
  return rc;
}

int virtAPIVersion(int* major, int* minor) {
  if (major == nullptr || minor == nullptr) {
    return fail(nullptr, VIRT_E_INCORRECT_VALUE, "virtAPIVersion: NULL output");
  }
  *major = kApiMajor;
  *minor = kApiMinor;
  return 0;
}

int virtGetControlerVersion(VirtContext VC, int* major, int* minor) {
  Context* vc = context_of(VC, major, "virtGetControlerVersion: NULL output");
  if (vc == nullptr || context_of(VC, minor, "virtGetControlerVersion: NULL output") == nullptr) {
    return -1;
  }
  const std::uint32_t version = vc->link()->controller_version();
  *major = static_cast<int>(hapticctrl::protocol::version_major(version));
  *minor = static_cast<int>(hapticctrl::protocol::version_minor(version));
  return 0;
}

int virtGetNbAxes(VirtContext VC, int* nbAxes) {
  if (context_of(VC, nbAxes, "virtGetNbAxes: NULL output") == nullptr) {
    return -1;
  }
  *nbAxes = kAxes;
  return 0;
}

int virtGetNumberOfAxes(VirtContext VC, int* nbAxes) {
  return virtGetNbAxes(VC, nbAxes);
}

int virtGetErrorCode(VirtContext VC) {
  return error_of(VC).code;
}

int virtGetError(VirtContext VC, int* error) {
  Context* vc = context_of(VC, error, "virtGetError: NULL output");
  if (vc == nullptr) {
    return -1;
  }
  *error = vc->error.code;
  return 0;
}

char* virtGetErrorMessage(int code) {
  // Indexed by VirtuoseAPI's codes, 0 to 22; hapticctrl's own from 100.
  static char kTexts[][40] = {// NOLINT(*-avoid-c-arrays): the C API returns char*
                              "no error",
                              "out of memory",
                              "communication failure",
                              "invalid context",
                              "file not found",
                              "wrong format",
                              "time out",
                              "not implemented",
                              "variable not available",
                              "incorrect value",
                              "syntax error",
                              "hardware error",
                              "position discontinuity",
                              "library not found",
                              "periodic function error",
                              "performance counter error",
                              "major/minor version mismatch",
                              "wrong mode",
                              "mode not supported",
                              "call time error",
                              "incompatible version",
                              "incorrect virtual mechanism type",
                              "already called",
                              "controller busy",
                              "controller refused",
                              "unknown error"};
  constexpr int kHaptionCodes = VIRT_E_ALREADY_CALLED + 1;
  constexpr int kOwnFirst = VIRT_E_VIRTUOSE_BUSY;
  constexpr int kOwnCount = 2;
  if (code >= 0 && code < kHaptionCodes) {
    return kTexts[code];
  }
  if (code >= kOwnFirst && code < kOwnFirst + kOwnCount) {
    return kTexts[kHaptionCodes + code - kOwnFirst];
  }
  return kTexts[kHaptionCodes + kOwnCount];
}

const char* virtGetErrorDetail(VirtContext VC) {
  return error_of(VC).detail.data();
}

int virtSetDebugFlags(VirtContext VC, unsigned short flag) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  if ((flag & ~static_cast<unsigned>(DEBUG_SERVO | DEBUG_LOOP)) != 0U) {
    return fail(VC, VIRT_E_INCORRECT_VALUE, "virtSetDebugFlags: DEBUG_SERVO and DEBUG_LOOP only");
  }
  vc->debug_flags.store(flag, std::memory_order_relaxed);
  return 0;
}

int virtSetOutputFile(VirtContext VC, char* name) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  std::FILE* file = nullptr;
  if (name != nullptr) {
    file = std::fopen(name, "a");  // NOLINT(cppcoreguidelines-owning-memory): closed by Context
    if (file == nullptr) {
      return fail(VC, VIRT_E_FILE_NOT_FOUND, "virtSetOutputFile: cannot open the file to append");
    }
    std::setvbuf(file, nullptr, _IOLBF, BUFSIZ);  // whole lines, readable while the loop runs
  }
  const std::lock_guard lock(vc->mutex);
  if (vc->output != nullptr) {
    std::fclose(vc->output);  // NOLINT(cppcoreguidelines-owning-memory)
  }
  vc->output = file;
  return 0;
}

int virtDisplayHardwareStatus(VirtContext VC, FILE* fichier) {
  Context* vc = context_of(VC, fichier, "virtDisplayHardwareStatus: NULL file");
  if (vc == nullptr) {
    return -1;
  }
  const std::shared_ptr<Connection> link = vc->link();
  const StateSnapshot s = link->snapshot();
  const hapticctrl::client::LinkStatistics st = link->statistics();
  static constexpr const char* kCoreStates[] = {
      // NOLINT(*-avoid-c-arrays)
      "starting", "running", "fail-safe", "stopping", "stopped"};
  const char* core = s.core_state < 5 ? kCoreStates[s.core_state] : "unknown";
  const std::uint32_t version = link->controller_version();
  const int written = std::fprintf(
      fichier,
      "hapticctrl controller (protocol %u.%u), cycle %llu, period %.0f us\n"
      "  core %s, stop reason %u, power %s, emergency stop %s, fail-safe %s\n"
      "  handle %.4f %.4f %.4f m, state word 0x%08x\n"
      "  link: %llu answers, %llu lost, round trip %.0f us (max %.0f), jitter %.0f us\n",
      hapticctrl::protocol::version_major(version), hapticctrl::protocol::version_minor(version),
      static_cast<unsigned long long>(s.cycle),
      static_cast<double>(link->controller_period_ns()) / 1e3, core, s.stop_reason,
      s.powered() ? "on" : "off", s.emergency_stop() ? "latched" : "clear",
      s.fail_safe() ? "yes" : "no", s.handle_pose[0], s.handle_pose[1], s.handle_pose[2],
      s.state_word, static_cast<unsigned long long>(st.answers_received),
      static_cast<unsigned long long>(st.answers_lost), st.rtt_mean_us, st.rtt_max_us,
      st.jitter_us);
  if (written < 0) {
    return fail(VC, VIRT_E_COMMUNICATION_FAILURE, "virtDisplayHardwareStatus: cannot write");
  }
  return 0;
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
