#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <thread>
#include <vector>

#include <unistd.h>

namespace rt {

Progress::Progress(std::string label, long total, bool enabled)
    : label_(std::move(label)), total_(std::max(total, 1L)), enabled_(enabled && ::isatty(2)),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

void Progress::advance(long amount) {
    const long done = done_.fetch_add(amount) + amount;
    if (!enabled_) return;
    if (std::chrono::steady_clock::now() - start_ < std::chrono::seconds(1)) return;
    draw(done);
}

void Progress::draw(long done) {
    const int percent = int(100 * done / total_);
    std::lock_guard lock(mutex_);
    if (percent == last_percent_) return;
    last_percent_ = percent;
    shown_ = true;
    const int width = 40, filled = width * percent / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled, "########################################",
                 width - filled, "", percent);
    std::fflush(stderr);
}

void Progress::finish() {
    std::lock_guard lock(mutex_);
    if (shown_) std::fprintf(stderr, "\n");
    shown_ = false;
}

int resolve_thread_count(int requested) {
    if (requested > 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

void parallel_rows(int rows, int threads, Progress& progress, RayCounters& counters,
                   const std::function<void(int, RayCounters&)>& body) {
    threads = std::clamp(threads, 1, std::max(rows, 1));
    std::atomic<int> next{0};
    std::vector<RayCounters> per_thread(static_cast<std::size_t>(threads));
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
    auto worker = [&](int id) {
        try {
            for (int row = next++; row < rows; row = next++) {
                body(row, per_thread[std::size_t(id)]);
                progress.advance();
            }
        } catch (...) {
            errors[std::size_t(id)] = std::current_exception();
            next = rows;   // stop the others early
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker, i);
    worker(0);
    for (auto& t : pool) t.join();
    for (auto& e : errors)
        if (e) std::rethrow_exception(e);
    for (const auto& c : per_thread) counters.add(c);
}

}  // namespace rt
