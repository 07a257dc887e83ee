#pragma once
/// @file peer_stats.hpp
/// The peer benchmark's figures from its runs (peer_runner.hpp): percentiles, medians over
/// repeated runs, CPU time per 1000 messages, the publish cost per stall phase, and the JSON
/// object of one case. Benchmark code.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "peers/peer_runner.hpp"

namespace hapticctrl::bench {

/// Writes one case: `latency` are the repeated latency runs (1 kHz, `messages` each), `cpu_1k`
/// and `cpu_10k` the CPU-time runs, `stall` the run with the reader stopped then killed.
void print_case_json(std::FILE* out, const std::string& transport, const char* mode,
                     std::uint32_t messages, const std::vector<RunResult>& latency,
                     const RunResult& cpu_1k, const RunResult& cpu_10k, const RunResult& stall);

}  // namespace hapticctrl::bench
