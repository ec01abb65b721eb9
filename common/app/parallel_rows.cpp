#include "parallel_rows.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace rt {

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
