#include "fuzz_gltf_target.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/scene/gltf/gltf_io.h"

namespace {

// One scratch file per process (the loader reads paths, and a .glb or .gltf extension picks the parser). Buffers
// and images by relative URI resolve next to it, in the same private folder.
const std::filesystem::path& scratch_dir() {
    static const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("rt_fuzz_gltf_" + std::to_string(::getpid()));
    return dir;
}

void remove_scratch_dir() {
    std::error_code ec;
    std::filesystem::remove_all(scratch_dir(), ec);
}

std::string scratch_path(bool binary) {
    static const std::filesystem::path& dir = []() -> const std::filesystem::path& {
        std::filesystem::create_directories(scratch_dir());
        std::atexit(remove_scratch_dir);
        return scratch_dir();
    }();
    return (dir / (binary ? "input.glb" : "input.gltf")).string();
}

std::size_t accepted = 0;

}  // namespace

std::size_t fuzz_gltf_accepted_inputs() { return accepted; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string path = scratch_path(binary);
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        const rt::SceneAsset asset = rt::load_gltf(path);
        rt::FlattenOptions options;
        options.max_triangles = 200'000;   // keeps each input fast; the budget check itself is what is exercised
        for (float t : {0.0f, 0.37f}) {
            options.time = t;
            const rt::Scene scene = rt::flatten(asset, options);
            // Every flattened array agrees with the triangle count.
            if (scene.positions.size() != 3 * scene.triangle_count() || scene.normals.size() != scene.positions.size())
                std::abort();
        }
        ++accepted;
    } catch (const rt::SceneError&) {
        // the expected answer to bad input
    }
    return 0;
}
