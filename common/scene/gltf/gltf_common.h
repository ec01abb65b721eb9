// Helpers shared by the glTF loader (gltf_loader.h and its files) and saver (gltf_save.cpp). Internal to rt_scene.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace rt::gltf_detail {

inline std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// tinygltf reports several lines; the user gets one.
inline std::string one_line(const std::string& text) {
    std::string out;
    bool pending_separator = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pending_separator = !out.empty();
            continue;
        }
        if (pending_separator) { out += "; "; pending_separator = false; }
        out += c;
    }
    while (!out.empty() && std::isspace(static_cast<unsigned char>(out.back()))) out.pop_back();
    return out.empty() ? "unknown error" : out;
}

// Thrown inside the loader and the saver; load_gltf and save_gltf add the file name.
struct Invalid {
    std::string reason;
};
[[noreturn]] inline void invalid(const std::string& reason) { throw Invalid{reason}; }

}  // namespace rt::gltf_detail
