// A progress bar on stderr that appears only once a render has taken longer than a second (and never with --quiet).
// (parallel_rows.h feeds it from stage 01's rows, the wavefront pipeline from its batches.)
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

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

}  // namespace rt
