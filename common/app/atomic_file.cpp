#include "atomic_file.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <random>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace rt {

namespace fs = std::filesystem;

namespace {

// The files a signal handler removes. A fixed array, written only under `registry_mutex`; the handler reads it
// without locking, which is safe because a slot's path is complete before `used` turns true (release/acquire).
struct Slot {
    std::atomic<bool> used{false};
    char path[PATH_MAX] = {};
};
std::array<Slot, 16> slots;   // a run has at most a few outputs in flight, each with one or two temporaries
std::mutex registry_mutex;

void remember(const std::string& path) {
    std::lock_guard lock(registry_mutex);
    if (path.size() >= PATH_MAX) throw std::runtime_error("cannot write " + path + ": path too long");
    for (Slot& s : slots)
        if (!s.used.load()) {
            std::memcpy(s.path, path.c_str(), path.size() + 1);
            s.used.store(true, std::memory_order_release);
            return;
        }
    throw std::logic_error("too many temporary files at once");
}

void forget(const std::string& path) {
    std::lock_guard lock(registry_mutex);
    for (Slot& s : slots)
        if (s.used.load() && path == s.path) {
            s.used.store(false, std::memory_order_release);
            return;
        }
}

// Async-signal-safe: only unlink, signal and raise.
extern "C" void remove_temporaries_and_die(int sig) {
    for (Slot& s : slots)
        if (s.used.load(std::memory_order_acquire)) ::unlink(s.path);
    ::signal(sig, SIG_DFL);
    ::raise(sig);   // delivered when the handler returns: the process ends as the signal asked
}

std::string random_word(std::size_t length) {
    static std::mutex mutex;
    static std::mt19937_64 engine{std::random_device{}()};
    static const char letters[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    std::lock_guard lock(mutex);
    std::uniform_int_distribution<int> pick(0, int(sizeof letters) - 2);
    std::string word;
    for (std::size_t i = 0; i < length; ++i) word += letters[pick(engine)];
    return word;
}

std::string error_text(int error) { return std::system_category().message(error); }

}  // namespace

std::string create_temporary(const std::string& path) {
    const fs::path p(path);
    // Short parts, so a target name near the 255-byte limit still has a temporary that fits.
    const std::string stem = p.stem().string().substr(0, 32);
    const std::string ext = p.extension().string().substr(0, 16);
    for (int attempt = 0; attempt < 100; ++attempt) {
        const std::string name = (p.parent_path() / ("." + stem + ".tmp-" + random_word(10) + ext)).string();
        // The user's path in the message, not the temporary's (which is longer by its prefix and random part).
        if (name.size() >= PATH_MAX) throw std::runtime_error("cannot write " + path + ": path too long");
        remember(name);   // before the file exists, so no signal can leave it behind
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        const int error = errno;
        if (fd >= 0) {
            ::close(fd);
            return name;
        }
        forget(name);
        if (error != EEXIST) throw std::runtime_error("cannot write " + path + ": " + error_text(error));
    }
    throw std::runtime_error("cannot write " + path + ": no unused temporary name");
}

void commit_temporary(const std::string& temporary, const std::string& path) {
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const int error = errno;
        discard_temporary(temporary);
        throw std::runtime_error("cannot write " + path + ": " + error_text(error));
    }
    forget(temporary);
}

void discard_temporary(const std::string& temporary) {
    ::unlink(temporary.c_str());
    forget(temporary);
}

void remove_on_interrupt(const std::string& path) { remember(path); }
void forget_on_interrupt(const std::string& path) { forget(path); }

void install_temporary_cleanup() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction old {};
            ::sigaction(sig, nullptr, &old);
            if (old.sa_handler == SIG_IGN) continue;
            struct sigaction action {};
            action.sa_handler = remove_temporaries_and_die;
            sigfillset(&action.sa_mask);
            ::sigaction(sig, &action, nullptr);
        }
    });
}

}  // namespace rt
