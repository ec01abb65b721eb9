// A parallel loop over image rows (stage 01's CPU tracer), with per-thread ray counters and a progress bar fed by
// the rows done; and the --threads rule.
#pragma once

#include <functional>

#include "common/trace/ray.h"
#include "progress.h"

namespace rt {

// Number of threads for --threads N (0 = all hardware threads).
int resolve_thread_count(int requested);

// Calls body(row, counters) for every row in [0, rows), rows handed out dynamically to `threads` threads; each
// thread's counters are added into `counters` at the end. Exceptions in a worker are rethrown in the caller.
void parallel_rows(int rows, int threads, Progress& progress, RayCounters& counters,
                   const std::function<void(int row, RayCounters& counters)>& body);

}  // namespace rt
