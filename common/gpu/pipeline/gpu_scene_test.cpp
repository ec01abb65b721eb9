// GpuScene's texture storage: unpadded (memory is the sum of the texture sizes) and a clear error past the limit.
#include <gtest/gtest.h>

#include "common/scene/gltf/gltf_io.h"
#include "gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "common/gpu/gl/storage_limit.h"

namespace rt::gpu {
namespace {

Texture solid_texture(int width, int height, std::uint8_t value) {
    Texture t;
    t.name = std::to_string(width) + "x" + std::to_string(height);
    t.width = width;
    t.height = height;
    t.rgba8.assign(std::size_t(width) * std::size_t(height) * 4, value);
    return t;
}

// One large and many tiny textures: a texture array padded to the largest would take 201 times the large one.
TEST(GpuScene, TextureBytesAreTheSumOfTheTextureSizes) {
    test_context();
    Scene scene;
    scene.textures.push_back(solid_texture(1024, 1024, 7));
    std::size_t texel_bytes = 1024 * 1024 * 4;
    for (int i = 0; i < 200; ++i) {
        scene.textures.push_back(solid_texture(1 + i % 3, 1 + i % 2, std::uint8_t(i)));
        texel_bytes += std::size_t(1 + i % 3) * std::size_t(1 + i % 2) * 4;
    }
    GpuScene gpu;
    gpu.upload(scene);
    const std::size_t tables = 2 * 256 * sizeof(float) + scene.textures.size() * sizeof(GpuTextureInfo);
    EXPECT_EQ(gpu.texture_bytes(), tables + texel_bytes);
    EXPECT_LE(gpu.bytes(), gpu.texture_bytes() + 4096);   // an empty scene's other buffers are tiny
    // The last tiny texture's texels sit right after the one before it.
    const auto words = gpu.textures().download<std::uint32_t>(1, gpu.texture_bytes() / 4 - 1);
    EXPECT_EQ(words[0], 0xc7c7c7c7u);   // texture 200: value 199, 2 x 1 texels
}

TEST(GpuScene, TexturesBeyondTheStorageBlockLimitAreAOneLineError) {
    test_context();
    const std::size_t limit = max_storage_block_bytes();
    Scene scene;
    scene.textures.push_back(solid_texture(4096, int(limit / (4096 * 4)), 1));   // exactly the limit, + the tables
    GpuScene gpu;
    try {
        gpu.upload(scene);
        FAIL() << "no error for textures of " << limit << " bytes";
    } catch (const SceneError& e) {   // the stages report it as bad input: one line, exit 2
        const std::string message = e.what();
        EXPECT_NE(message.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << message;
        EXPECT_NE(message.find(std::to_string(limit)), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace rt::gpu
