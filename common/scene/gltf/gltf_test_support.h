// Test support for the glTF loader's tests (gltf_io_test.cpp, gltf_accessors_test.cpp): a temporary folder, files
// written byte for byte, buffers as base64 data URIs, and the one-line SceneError check. Header-only, for tests.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "gltf_io.h"

namespace rt::gltf_test {

namespace fs = std::filesystem;

// A fresh folder per test under the system temp folder, removed afterwards.
class TempDir {
  public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::random_device rd;
        path_ = fs::temp_directory_path() /
                ("rt_scene_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(rd()));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

inline void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

inline std::string base64(const std::vector<unsigned char>& data) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < data.size(); i += 3) {
        const unsigned v = unsigned(data[i]) << 16 | (i + 1 < data.size() ? unsigned(data[i + 1]) << 8 : 0u) |
                           (i + 2 < data.size() ? unsigned(data[i + 2]) : 0u);
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < data.size() ? table[(v >> 6) & 63] : '=';
        out += i + 2 < data.size() ? table[v & 63] : '=';
    }
    return out;
}

template <class T>
void append(std::vector<unsigned char>& bytes, const std::vector<T>& values) {
    const auto* p = reinterpret_cast<const unsigned char*>(values.data());
    bytes.insert(bytes.end(), p, p + values.size() * sizeof(T));
}

inline std::string data_uri(const std::vector<unsigned char>& bytes) {
    return "data:application/octet-stream;base64," + base64(bytes);
}

inline void expect_one_line_scene_error(const std::string& path, const std::string& must_contain) {
    try {
        load_gltf(path);
        FAIL() << "no SceneError for " << path;
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_EQ(what.rfind("cannot load scene " + path + ": ", 0), 0u) << what;
        EXPECT_NE(what.find(must_contain), std::string::npos) << what;
    }
}

}  // namespace rt::gltf_test
