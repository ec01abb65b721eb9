#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <utility>

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

}  // namespace rt
