// The C API's periodic function: run on the connection's receive thread after the controller's
// answers, every `decimation` of them, with the commands it set sent right after it returns.
#include <algorithm>
#include <cmath>

#include "virtuose_context.hpp"

using hapticctrl::client::virtuose::Context;
using hapticctrl::client::virtuose::context_of;
using hapticctrl::client::virtuose::fail;
using hapticctrl::client::virtuose::periodic_callback;

extern "C" {
// NOLINTBEGIN(readability-identifier-naming): VirtuoseAPI's names

int virtSetPeriodicFunction(VirtContext VC, void (*fn)(VirtContext, void*), float* period,
                            void* arg) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  if (fn == nullptr || period == nullptr || !std::isfinite(*period) || *period <= 0.0F) {
    return fail(VC, VIRT_E_INCORRECT_VALUE, "virtSetPeriodicFunction: NULL function or bad period");
  }
  if (vc->loop_running.load()) {
    return fail(VC, VIRT_E_WRONG_MODE, "virtSetPeriodicFunction: stop the loop first");
  }
  const double cycle_s = static_cast<double>(vc->link()->controller_period_ns()) / 1e9;
  vc->decimation =
      cycle_s > 0.0
          ? static_cast<unsigned>(std::max(1L, std::lround(static_cast<double>(*period) / cycle_s)))
          : 1U;
  *period = static_cast<float>(static_cast<double>(vc->decimation) * cycle_s);  // the one used
  vc->periodic = fn;
  vc->periodic_arg = arg;
  return 0;
}

int virtStartLoop(VirtContext VC) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  if (vc->periodic == nullptr) {
    return fail(VC, VIRT_E_WRONG_MODE, "virtStartLoop: call virtSetPeriodicFunction first");
  }
  const std::lock_guard control(vc->loop_control);
  vc->loop_running.store(true);
  return vc->guarded([&] { vc->link()->start_loop(periodic_callback(vc)); });
}

int virtStopLoop(VirtContext VC) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  if (vc->in_periodic_function()) {
    // From the function itself: the loop ends when it returns (Connection::stop_loop). Not
    // under loop_control, which a virtStartLoop on another thread may hold while it waits for
    // this function to return (a lock-order inversion ThreadSanitizer found, 2026-12-06).
    vc->link()->stop_loop();
    vc->loop_running.store(false);
    return 0;
  }
  const std::lock_guard control(vc->loop_control);
  vc->link()->stop_loop();
  vc->loop_running.store(false);
  return 0;
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
