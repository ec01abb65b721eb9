#include "gltf_files.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rt::gltf_detail {

namespace {

std::string what_is_wrong(const struct stat& st) {
    if (S_ISREG(st.st_mode)) return "";
    if (S_ISDIR(st.st_mode)) return "is a folder, not a file";
    if (S_ISFIFO(st.st_mode)) return "is a FIFO (named pipe), not a regular file";
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "is a device, not a regular file";
    if (S_ISSOCK(st.st_mode)) return "is a socket, not a regular file";
    return "is not a regular file";
}

// Every path "exists": read() then says what is wrong with it, and tinygltf never falls back to looking the URI up
// in the current folder.
bool exists(const std::string&, void*) { return true; }

std::string expand(const std::string& path, void*) { return path; }   // no ~ or $VAR expansion in URIs

bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto& reads = *static_cast<FileReads*>(user);
    const std::string problem = read_regular_file(path, *out);
    if (problem.empty()) {
        reads.files.push_back(path);
        return true;
    }
    if (reads.error.empty()) reads.error = "'" + path + "': " + problem;
    if (err) *err += problem;
    return false;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader writes nothing";
    return false;
}

}  // namespace

std::string read_regular_file(const std::string& path, std::vector<unsigned char>& bytes) {
    bytes.clear();
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) return errno == ENOENT ? "no such file" : std::strerror(errno);
    if (std::string problem = what_is_wrong(st); !problem.empty()) return problem;
    // O_NONBLOCK: should the path have become a FIFO since the check, open() still returns at once.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return std::strerror(errno);
    std::string problem;
    if (::fstat(fd, &st) != 0) problem = std::strerror(errno);
    else problem = what_is_wrong(st);
    if (problem.empty() && std::uint64_t(st.st_size) > kMaxInputFileBytes) problem = "is larger than 4 GiB";
    if (problem.empty()) {
        bytes.resize(std::size_t(st.st_size));
        std::size_t got = 0;
        while (got < bytes.size()) {
            const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) { problem = std::strerror(errno); break; }
            if (n == 0) break;   // the file shrank while being read
            got += std::size_t(n);
        }
        bytes.resize(got);
    }
    ::close(fd);
    if (!problem.empty()) bytes.clear();
    return problem;
}

tinygltf::FsCallbacks regular_file_callbacks(FileReads& reads) {
    tinygltf::FsCallbacks fs{};
    fs.FileExists = exists;
    fs.ExpandFilePath = expand;
    fs.ReadWholeFile = read;
    fs.WriteWholeFile = refuse_write;
    fs.user_data = &reads;
    return fs;
}

}  // namespace rt::gltf_detail
