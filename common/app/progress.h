// A progress bar on stderr that appears only once a render has taken longer than a second (and never with --quiet),
// and a parallel loop over image rows that feeds it.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>

#include "../trace/ray.h"

namespace rt {

class Progress {
public:
    Progress(std::string label, long total, bool enabled);
    ~Progress();
    void advance(long amount = 1);   // thread-safe
    void finish();

private:
    void draw(long done);
    std::string label_;
    long total_;
    bool enabled_;
    std::atomic<long> done_{0};
    std::chrono::steady_clock::time_point start_;
    std::mutex mutex_;
    bool shown_ = false;
    int last_percent_ = -1;
};

// Number of threads for --threads N (0 = all hardware threads).
int resolve_thread_count(int requested);

// Calls body(row, counters) for every row in [0, rows), rows handed out dynamically to `threads` threads; each
// thread's counters are added into `counters` at the end. Exceptions in a worker are rethrown in the caller.
void parallel_rows(int rows, int threads, Progress& progress, RayCounters& counters,
                   const std::function<void(int row, RayCounters& counters)>& body);

}  // namespace rt
