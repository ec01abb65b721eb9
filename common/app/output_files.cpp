#include "output_files.h"

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <sys/stat.h>
#include <unistd.h>

#include "atomic_file.h"

namespace rt {

namespace fs = std::filesystem;

namespace {

std::string error_text(int error) { return std::system_category().message(error); }

std::string describe(const OutputPath& o) { return o.option + " " + o.path; }

// The reason in atomic_file.h's "cannot write PATH: reason", for a message that names the option too.
std::string reason_of(const std::runtime_error& e, const OutputPath& output) {
    const std::string what = e.what(), prefix = "cannot write " + output.path + ": ";
    return what.starts_with(prefix) ? what.substr(prefix.size()) : what;
}

[[noreturn]] void refuse(const OutputPath& o, const std::string& problem) {
    throw std::invalid_argument(describe(o) + ": " + problem);
}

// A file's identity: two paths with the same device and inode are the same file (hard links, links, "a/../b").
using FileId = std::pair<dev_t, ino_t>;

// Checks the folder and the target of one output; returns the target's identity when it exists.
std::optional<FileId> check_target(const OutputPath& o) {
    const fs::path path(o.path);
    const std::string dir = path.parent_path().empty() ? "." : path.parent_path().string();
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0) {
        const int error = errno;
        if (error == ENOENT) refuse(o, "folder " + dir + " does not exist");
        refuse(o, "folder " + dir + ": " + error_text(error));
    }
    if (!S_ISDIR(st.st_mode)) refuse(o, dir + " is not a folder");
    if (path.filename().empty() || path.filename() == "." || path.filename() == "..") refuse(o, "not a file name");
    if (::lstat(o.path.c_str(), &st) != 0) {
        const int error = errno;
        if (error == ENOENT) return std::nullopt;
        refuse(o, error_text(error));
    }
    if (S_ISLNK(st.st_mode)) refuse(o, "is a symbolic link; not replacing it (name the file it points to)");
    if (S_ISDIR(st.st_mode)) refuse(o, "is a folder");
    if (!S_ISREG(st.st_mode)) refuse(o, "is not a regular file (a FIFO, socket or device); not replacing it");
    // No write bit for anyone, or none for us: read-only, even for root (who may write regardless).
    if ((st.st_mode & 0222) == 0 || ::access(o.path.c_str(), W_OK) != 0) refuse(o, "is read-only; not replacing it");
    return FileId{st.st_dev, st.st_ino};
}

// A canonical spelling of a path that may not exist yet, for comparing outputs that do not exist.
std::string canonical_name(const std::string& path) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (!ec) return p.string();
    const fs::path absolute = fs::absolute(path, ec);
    return (ec ? fs::path(path) : absolute).lexically_normal().string();
}

}  // namespace

void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs) {
    std::map<FileId, std::string> input_ids;
    for (const std::string& input : inputs) {
        struct stat st {};
        if (::stat(input.c_str(), &st) == 0) input_ids.emplace(FileId{st.st_dev, st.st_ino}, input);
    }
    std::map<std::string, const OutputPath*> by_name;
    std::map<FileId, const OutputPath*> by_id;
    for (const OutputPath& o : outputs) {
        const std::optional<FileId> id = check_target(o);
        if (id) {
            if (const auto in = input_ids.find(*id); in != input_ids.end())
                refuse(o, "is the scene's input file " + in->second + "; not overwriting it");
            if (const auto [it, fresh] = by_id.emplace(*id, &o); !fresh)
                refuse(o, "is the same file as " + describe(*it->second));
        }
        if (const auto [it, fresh] = by_name.emplace(canonical_name(o.path), &o); !fresh)
            refuse(o, "is the same file as " + describe(*it->second));
    }
}

RunOutputs::RunOutputs() { install_temporary_cleanup(); }

RunOutputs::~RunOutputs() {
    for (const Pending& p : pending_) discard_temporary(p.temporary);
    if (kept_) return;
    for (const std::string& target : completed_) ::unlink(target.c_str());
}

void RunOutputs::reserve(const OutputPath& output) {
    for (const Pending& p : pending_)
        if (p.output.path == output.path) return;
    try {
        pending_.push_back({output, create_temporary(output.path)});
    } catch (const std::runtime_error& e) {
        refuse(output, reason_of(e, output));
    }
}

void RunOutputs::write(const OutputPath& output, const std::function<void(const std::string&)>& write) {
    reserve(output);
    const auto it = std::find_if(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.output.path == output.path; });
    const Pending p = *it;
    pending_.erase(it);
    try {
        write(p.temporary);
    } catch (const std::exception& e) {
        discard_temporary(p.temporary);
        // The writer's message may name the temporary: say the user's path, and keep it on one line.
        std::string reason = e.what();
        for (std::size_t at; (at = reason.find(p.temporary)) != std::string::npos;)
            reason.replace(at, p.temporary.size(), output.path);
        std::replace(reason.begin(), reason.end(), '\n', ' ');
        throw std::runtime_error("cannot write " + describe(output) + ": " + reason);
    }
    try {
        commit_temporary(p.temporary, output.path);
    } catch (const std::runtime_error& e) {   // the rename failed (EBUSY, EISDIR, ...): the temporary is gone
        throw std::runtime_error("cannot write " + describe(output) + ": " + reason_of(e, output));
    }
    completed_.push_back(output.path);
}

void RunOutputs::keep() { kept_ = true; }

}  // namespace rt
