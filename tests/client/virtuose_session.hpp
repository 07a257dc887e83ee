#pragma once
// A C API session on a ControllerStack (the real core and bridge on loopback), closed at the
// end of the test whatever happened.
#include <gtest/gtest.h>

#include <string>

#include "hapticctrl/virtuose_api.h"
#include "support/controller_stack.hpp"

namespace hapticctrl::test {

inline std::string url(const ControllerStack& stack) {
  return "udpxdr://127.0.0.1:" + std::to_string(stack.port());
}

class VirtuoseSession {
 public:
  explicit VirtuoseSession(const ControllerStack& stack) : vc_(virtOpen(url(stack).c_str())) {}
  VirtuoseSession(const VirtuoseSession&) = delete;
  VirtuoseSession& operator=(const VirtuoseSession&) = delete;
  VirtuoseSession(VirtuoseSession&&) = delete;
  VirtuoseSession& operator=(VirtuoseSession&&) = delete;
  ~VirtuoseSession() {
    if (vc_ != nullptr) {
      virtSetPowerOn(vc_, 0);
      virtClose(vc_);
    }
  }
  [[nodiscard]] VirtContext get() const { return vc_; }
  [[nodiscard]] bool open() const { return vc_ != nullptr; }
  /// The context's detailed error, for failure messages.
  [[nodiscard]] std::string detail() const { return virtGetErrorDetail(vc_); }

 private:
  VirtContext vc_;
};

}  // namespace hapticctrl::test
