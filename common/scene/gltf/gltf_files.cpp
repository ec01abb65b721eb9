#include "gltf_files.h"

#include <algorithm>
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

// A path as an error message shows it: whole up to 200 characters, else its start and its end.
std::string shown(const std::string& path) {
    if (path.size() <= 200) return path;
    std::string out(path, 0, 120);
    out.append("...").append(path, path.size() - 60);
    return out;
}

bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto& reads = *static_cast<FileReads*>(user);
    // tinygltf decodes the data URIs glTF 2.0 allows (3.9) and hands any other to the callbacks as a file in the
    // glTF file's folder (base_dir/URI).
    std::string uri = path;
    if (!reads.base_dir.empty() && uri.rfind(reads.base_dir, 0) == 0) {
        uri.erase(0, reads.base_dir.size());
        if (reads.base_dir.back() != '/' && !uri.empty() && uri.front() == '/') uri.erase(0, 1);
    }
    if (uri.rfind("data:", 0) == 0) {
        const std::string problem = "a data URI of a media type glTF 2.0 does not allow (images: image/png or "
                                    "image/jpeg; buffers: application/octet-stream or application/gltf-buffer)";
        const std::string media_type = uri.substr(0, std::min<std::size_t>(uri.find(','), 60));   // "data:...;base64"
        if (reads.error.empty()) reads.error = "'" + media_type + ",...': " + problem;
        if (err) *err += problem;
        return false;
    }
    const std::string problem = read_regular_file(path, *out);
    if (problem.empty()) {
        reads.files.push_back(path);
        return true;
    }
    if (reads.error.empty()) reads.error = "'" + shown(path).append("': ") + problem;
    if (err) *err += problem;
    return false;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader writes nothing";
    return false;
}

std::uint32_t be16(const unsigned char* b, std::size_t at) { return std::uint32_t(b[at]) << 8 | b[at + 1]; }
std::uint32_t be32(const unsigned char* b, std::size_t at) { return be16(b, at) << 16 | be16(b, at + 2); }

bool is_png(const unsigned char* b, std::size_t n) { return n >= 24 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0; }
bool is_jpeg(const unsigned char* b, std::size_t n) { return n >= 4 && b[0] == 0xFF && b[1] == 0xD8; }

// Width and height from a PNG (IHDR) or JPEG (first SOFn segment) header; false when there is none.
bool image_size(const unsigned char* b, std::size_t n, std::uint32_t& width, std::uint32_t& height) {
    if (is_png(b, n)) {
        width = be32(b, 16);
        height = be32(b, 20);
        return true;
    }
    for (std::size_t at = 2; at + 9 <= n;) {   // segments: FF, marker, 16-bit length (including itself), data
        if (b[at] != 0xFF) return false;
        const unsigned marker = b[at + 1];
        const bool start_of_frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
                                    marker != 0xCC;   // C4, C8, CC: Huffman and arithmetic tables, not frames
        if (start_of_frame) {
            height = be16(b, at + 5);
            width = be16(b, at + 7);
            return true;
        }
        at += 2 + be16(b, at + 2);
    }
    return false;
}

// Whether a JPEG's markers reach its end-of-image marker (EOI, FF D9; ITU-T T.81, B.1): segments carry a 16-bit
// length, and after each start of scan (SOS, FF DA) the entropy-coded data runs to the next marker that is neither a
// stuffed FF 00 nor a restart marker (FF D0-D7). stb_image decodes a JPEG cut short without a word (it pads the
// missing data), so a truncated file would be rendered with a made-up texture.
bool jpeg_reaches_end(const unsigned char* b, std::size_t n) {
    auto restart = [](unsigned marker) { return marker >= 0xD0 && marker <= 0xD7; };
    for (std::size_t at = 2; at + 1 < n;) {
        if (b[at] != 0xFF) return false;
        const unsigned marker = b[at + 1];
        if (marker == 0xD9) return true;
        if (marker == 0xFF) {   // a fill byte before a marker
            ++at;
            continue;
        }
        if (restart(marker) || marker == 0x01) {   // markers without a segment
            at += 2;
            continue;
        }
        if (at + 4 > n) return false;
        at += 2 + be16(b, at + 2);
        if (marker == 0xDA)
            while (at + 1 < n && !(b[at] == 0xFF && b[at + 1] != 0x00 && !restart(b[at + 1]))) ++at;
    }
    return false;
}

}  // namespace

bool load_image_within_limits(tinygltf::Image* image, int index, std::string* err, std::string* warn, int req_width,
                              int req_height, const unsigned char* bytes, int size, void* user_data) {
    auto& reads = *static_cast<FileReads*>(user_data);
    const std::size_t n = size > 0 ? std::size_t(size) : 0;
    // tinygltf sets the URI of an image file before decoding it; a data URI or a buffer view's image has none.
    const std::string name = "image " + std::to_string(index) + (image->uri.empty() ? "" : " (" + image->uri + ")");
    if (!is_png(bytes, n) && !is_jpeg(bytes, n)) {
        // glTF 2.0 images are PNG or JPEG (3.8.4.1); other formats come with extensions (EXT_texture_webp,
        // KHR_texture_basisu) that this renderer does not read. stb_image would decode BMP, GIF, PSD, TGA, HDR and
        // more, of any size the header claims: such an image is left undecoded, and a texture that uses it as its
        // source is refused (Loader::texture).
        if (warn) *warn += name + " is not a PNG or JPEG image: not decoded\n";
        return true;
    }
    std::string problem;
    std::uint32_t width = 0, height = 0;
    if (!image_size(bytes, n, width, height))
        problem = "is a JPEG without a frame header";
    else if (width > std::uint32_t(kMaxImageSide) || height > std::uint32_t(kMaxImageSide))
        problem = "is " + std::to_string(width) + " x " + std::to_string(height) + " pixels, more than " +
                  std::to_string(kMaxImageSide) + " on a side";
    else if (reads.texels + std::uint64_t(width) * height > kMaxImageTexels)
        problem = "brings the file's images past " + std::to_string(kMaxImageTexels) + " pixels in all";
    else if (is_jpeg(bytes, n) && !jpeg_reaches_end(bytes, n))
        problem = "is a truncated JPEG (no end-of-image marker)";
    else if (is_jpeg(bytes, n) && std::uint64_t(n) * 8 < std::uint64_t((width + 7) / 8) * ((height + 7) / 8))
        // Each 8 x 8 block of a Huffman-coded JPEG takes at least one bit (its DC difference's code, T.81 F.1.2.1),
        // so fewer bits than blocks is a header that claims more pixels than the data holds (stb_image would pad).
        problem = "has too little data for its " + std::to_string(width) + " x " + std::to_string(height) + " pixels";
    else if (!tinygltf::LoadImageData(image, index, err, warn, req_width, req_height, bytes, size, nullptr))
        problem = std::string("cannot be decoded (a corrupt or truncated ") + (is_png(bytes, n) ? "PNG)" : "JPEG)");
    if (!problem.empty()) {
        if (reads.error.empty()) reads.error = name + " " + problem;
        if (err) *err += problem;
        return false;
    }
    reads.texels += std::uint64_t(width) * height;
    return true;
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
