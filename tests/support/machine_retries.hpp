#pragma once
/// Telling the machine's faults from the software's in multi-process tests (J5): each
/// ControllerStack notes, when it ends, what the machine did to its core (its measured periods,
/// the stalls it rode through, a fail-safe on missed deadlines), and
/// `retry_what_the_machine_disturbed` runs a test's attempts with their failures held back: an
/// attempt that failed while the machine measurably disturbed its core is tried again, and said,
/// with the failure it had; an attempt that failed on an undisturbed machine is the verdict. No
/// threshold changes: what changes is which attempts are judged.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>

#include "support/machine_disturbance.hpp"

namespace hapticctrl::test {

/// Runs `body(attempt)` up to `attempts` times until one is judged. The body returns false when
/// it already knows the machine spoiled the attempt (its core failed safe, its link was held
/// up); true when it judged. A judged attempt's failures are held back and retried when the
/// machine disturbed it; each retry is printed with its reason and first failure. When the
/// machine disturbed every attempt, nothing could be judged: the test is skipped, saying so.
inline void retry_what_the_machine_disturbed(const std::string& name, int attempts,
                                             const std::function<bool(int)>& body) {
  int lost = 0;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    attempt_disturbance() = {};
    ::testing::TestPartResultArray results;
    bool judged = false;
    {
      const ::testing::ScopedFakeTestPartResultReporter hold(
          ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
      judged = body(attempt);
    }
    const MachineDisturbance disturbance = attempt_disturbance();
    int failures = 0;
    std::string first;
    for (int i = 0; i < results.size(); ++i) {
      if (results.GetTestPartResult(i).failed() && failures++ == 0) {
        first = results.GetTestPartResult(i).summary();
      }
    }
    if (judged && (failures == 0 || !disturbance.any())) {
      for (int i = 0; i < results.size(); ++i) {
        const ::testing::TestPartResult& r = results.GetTestPartResult(i);
        if (r.failed()) {
          ADD_FAILURE_AT(r.file_name() != nullptr ? r.file_name() : "?", r.line_number())
              << r.message();
        }
      }
      std::printf("%s: %d attempt(s) lost to the machine (this one %s: %s)\n", name.c_str(), lost,
                  disturbance.any() ? "disturbed" : "undisturbed", disturbance.text().c_str());
      ::testing::Test::RecordProperty("attempts_lost_to_the_machine", lost);
      return;
    }
    ++lost;
    if (judged) {
      std::printf(
          "%s: attempt %d failed while the machine disturbed its core (%s): tried again;"
          " its first failure: %s\n",
          name.c_str(), attempt + 1, disturbance.text().c_str(), first.c_str());
    }
  }
  GTEST_SKIP() << "the machine disturbed all " << attempts
               << " attempts (stalls, a core failed safe on missed deadlines, a link held up):"
                  " nothing could be judged";
}

}  // namespace hapticctrl::test
