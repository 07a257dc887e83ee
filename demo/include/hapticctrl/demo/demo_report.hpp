#pragma once
/// @file demo_report.hpp
/// What the demo tells its user: one CSV row per step (--log), a status line, and the JSON
/// summary at the end (--json). Not for a cycle: they format and write.

#include <cstdint>
#include <cstdio>
#include <ostream>

#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/demo/demo_input.hpp"
#include "hapticctrl/demo/sphere_scene.hpp"

namespace hapticctrl::demo {

/// The CSV header: the columns write_log_row() writes.
void write_log_header(std::ostream& log);
/// One step: time, cycle, state word, the sphere's pose, velocity and contact force, the
/// coupling wrench, the wrench the user applies, the handle's position.
void write_log_row(std::ostream& log, double t, const client::StateSnapshot& s,
                   const SphereScene& scene, const AppliedWrench& applied);
/// One status line ended by `end` ("\r" to rewrite it in place on a terminal).
void print_status(FILE* out, double t, const client::StateSnapshot& s, const SphereScene& scene,
                  const char* end);
/// The run's summary as one JSON object on one line.
void print_summary_json(FILE* out, const client::StateSnapshot& s, const SphereScene& scene,
                        const client::LinkStatistics& st, std::uint64_t steps,
                        std::uint64_t reconnects, const char* ended);

}  // namespace hapticctrl::demo
