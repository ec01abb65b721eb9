// The files a glTF file refers to (buffers and images by URI), read for tinygltf through its FsCallbacks: only
// regular files, never blocking (a FIFO is refused before it is opened), and each one recorded.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace rt::gltf_detail {

// Largest image accepted, per side and for all images of a file together (docs/shading.md, "Limits"): 16384 is
// the usual GPU texture limit; 2^28 texels are 1 GiB as RGBA8. Checked from the PNG/JPEG header, before decoding.
constexpr int kMaxImageSide = 16384;
constexpr std::uint64_t kMaxImageTexels = std::uint64_t(1) << 28;

// What the callbacks saw while tinygltf loaded one file.
struct FileReads {
    std::vector<std::string> files;   // every file read, in order
    std::string error;                // the first refusal, one line naming the path ("" when none)
    std::uint64_t texels = 0;         // pixels of the images decoded so far
    std::string base_dir;             // the glTF file's folder, which tinygltf puts before each URI
};

// The image decoder tinygltf is given: a PNG or JPEG image has its size in the header checked against the limits
// above (and a JPEG its end), then is decoded with tinygltf's own (stb_image); any other format is left undecoded,
// with a warning. user_data is the FileReads.
bool load_image_within_limits(tinygltf::Image* image, int index, std::string* err, std::string* warn, int req_width,
                              int req_height, const unsigned char* bytes, int size, void* user_data);

// Callbacks that read through read_regular_file and record into `reads` (which must outlive the loading).
tinygltf::FsCallbacks regular_file_callbacks(FileReads& reads);

// Larger files are refused (a .glb cannot be larger either; glTF 2.0, 4.4.3).
constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t(1) << 32;

// Reads a whole regular file. Returns "" on success, else what is wrong with the path ("is a folder", "is a FIFO",
// "does not exist", ...). Opens with O_NONBLOCK after checking the type, and checks the type again on the open file.
std::string read_regular_file(const std::string& path, std::vector<unsigned char>& bytes);

}  // namespace rt::gltf_detail
