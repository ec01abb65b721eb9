// The files a glTF file refers to (buffers and images by URI), read for tinygltf through its FsCallbacks: only
// regular files, never blocking (a FIFO is refused before it is opened), and each one recorded.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace rt::gltf_detail {

// What the callbacks saw while tinygltf loaded one file.
struct FileReads {
    std::vector<std::string> files;   // every file read, in order
    std::string error;                // the first refusal, one line naming the path ("" when none)
};

// Callbacks that read through read_regular_file and record into `reads` (which must outlive the loading).
tinygltf::FsCallbacks regular_file_callbacks(FileReads& reads);

// Larger files are refused (a .glb cannot be larger either; glTF 2.0, 4.4.3).
constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t(1) << 32;

// Reads a whole regular file. Returns "" on success, else what is wrong with the path ("is a folder", "is a FIFO",
// "does not exist", ...). Opens with O_NONBLOCK after checking the type, and checks the type again on the open file.
std::string read_regular_file(const std::string& path, std::vector<unsigned char>& bytes);

}  // namespace rt::gltf_detail
