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

// Width and height from a PNG (IHDR) or JPEG (first SOFn segment) header; false for anything else.
bool image_size(const unsigned char* b, std::size_t n, std::uint32_t& width, std::uint32_t& height) {
    auto be16 = [&](std::size_t at) { return std::uint32_t(b[at]) << 8 | b[at + 1]; };
    auto be32 = [&](std::size_t at) { return be16(at) << 16 | be16(at + 2); };
    if (n >= 24 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0) {
        width = be32(16);
        height = be32(20);
        return true;
    }
    if (n < 4 || b[0] != 0xFF || b[1] != 0xD8) return false;
    for (std::size_t at = 2; at + 9 <= n;) {   // segments: FF, marker, 16-bit length (including itself), data
        if (b[at] != 0xFF) return false;
        const unsigned marker = b[at + 1];
        const bool start_of_frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
                                    marker != 0xCC;   // C4, C8, CC: Huffman and arithmetic tables, not frames
        if (start_of_frame) {
            height = be16(at + 5);
            width = be16(at + 7);
            return true;
        }
        at += 2 + be16(at + 2);
    }
    return false;
}

}  // namespace

bool load_image_within_limits(tinygltf::Image* image, int index, std::string* err, std::string* warn, int req_width,
                              int req_height, const unsigned char* bytes, int size, void* user_data) {
    auto& reads = *static_cast<FileReads*>(user_data);
    std::uint32_t width = 0, height = 0;
    if (size > 0 && image_size(bytes, std::size_t(size), width, height)) {
        std::string problem;
        if (width > std::uint32_t(kMaxImageSide) || height > std::uint32_t(kMaxImageSide))
            problem = "is " + std::to_string(width) + " x " + std::to_string(height) + " pixels, more than " +
                      std::to_string(kMaxImageSide) + " on a side";
        else if (reads.texels + std::uint64_t(width) * height > kMaxImageTexels)
            problem = "brings the file's images past " + std::to_string(kMaxImageTexels) + " pixels in all";
        if (!problem.empty()) {
            if (reads.error.empty()) reads.error = "image " + std::to_string(index) + " " + problem;
            if (err) *err += problem;
            return false;
        }
        reads.texels += std::uint64_t(width) * height;
    }
    return tinygltf::LoadImageData(image, index, err, warn, req_width, req_height, bytes, size, nullptr);
}

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
