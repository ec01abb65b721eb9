#include "atomic_file.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace rt {

namespace fs = std::filesystem;

std::string temporary_sibling(const std::string& path) {
    const fs::path p(path);
    std::string name = ".";
    name += p.stem().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    name += p.extension().string();
    return (p.parent_path() / name).string();
}

void commit_temporary(const std::string& temporary, const std::string& path) {
    std::error_code ec;
    fs::rename(temporary, path, ec);
    if (ec) {
        discard_temporary(temporary);
        throw std::runtime_error("cannot write " + path + ": " + ec.message());
    }
}

void discard_temporary(const std::string& temporary) {
    std::error_code ec;
    fs::remove(temporary, ec);
}

}  // namespace rt
