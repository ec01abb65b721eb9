// KHR_materials_volume, normalTexture, TANGENT and KHR_texture_transform in glTF files: what the loader reads from
// hand-written JSON, the round trip through save_gltf, and hostile values (docs/shading.md, "Values from files").
#include "gltf_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include <nlohmann/json.hpp>

#include "common/scene/builtin/builtin_scenes.h"

namespace rt {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class GltfSurface : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("rt_surface_" + std::string(info->name()) + "_" +
                                            std::to_string(std::random_device{}()));
        fs::create_directories(dir_);
        // One triangle: positions, then uvs, then tangents, in tri.bin.
        const float data[9 + 6 + 12] = {0, 0, 0, 1, 0, 0, 0, 1, 0,  0, 1, 1, 1, 0, 0,
                                        1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1};
        std::ofstream(file("tri.bin"), std::ios::binary).write(reinterpret_cast<const char*>(data), sizeof data);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    std::string file(const std::string& name) const { return (dir_ / name).string(); }

    // A one-triangle scene with uvs, tangents and one material whose JSON the test fills in.
    static json triangle(const json& material) {
        json doc = json::parse(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
            "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1,"TANGENT":2},"material":0}]}],
            "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
                         {"bufferView":0,"byteOffset":36,"componentType":5126,"count":3,"type":"VEC2"},
                         {"bufferView":0,"byteOffset":60,"componentType":5126,"count":3,"type":"VEC4"}],
            "bufferViews":[{"buffer":0,"byteLength":108}],"buffers":[{"uri":"tri.bin","byteLength":108}],
            "textures":[{"source":0}],
            "images":[{"uri":"data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNgaPj/HwAFgwKAfJ2hTQAAAABJRU5ErkJggg=="}]})");
        doc["materials"] = json::array({material});
        return doc;
    }
    SceneAsset load(const json& doc, std::string* warnings = nullptr) const {
        std::ofstream(file("scene.gltf")) << doc.dump();
        return load_gltf(file("scene.gltf"), warnings);
    }

    fs::path dir_;
};

TEST_F(GltfSurface, ReadsVolumeNormalTextureTangentsAndTransforms) {
    const json material = json::parse(R"({
        "normalTexture":{"index":0,"scale":-0.5,
                         "extensions":{"KHR_texture_transform":{"offset":[0.5,1],"rotation":0.25,"scale":[2,3]}}},
        "pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"scale":[4,4]}}}},
        "extensions":{"KHR_materials_transmission":{"transmissionFactor":1},
                      "KHR_materials_volume":{"thicknessFactor":0.5,"attenuationColor":[0.8,0.4,0.2],
                                              "attenuationDistance":0.25}}})");
    std::string warnings;
    const SceneAsset a = load(triangle(material), &warnings);
    EXPECT_EQ(warnings, "");
    const Material& m = a.materials.at(0);
    EXPECT_EQ(m.normal_texture, 0);
    EXPECT_EQ(m.normal_scale, -0.5f);
    EXPECT_EQ(m.normal_transform.offset, glm::vec2(0.5f, 1.0f));
    EXPECT_EQ(m.normal_transform.rotation, 0.25f);
    EXPECT_EQ(m.normal_transform.scale, glm::vec2(2.0f, 3.0f));
    EXPECT_EQ(m.base_color_transform.scale, glm::vec2(4.0f));
    EXPECT_EQ(m.thickness, 0.5f);
    EXPECT_EQ(m.attenuation_color, glm::vec3(0.8f, 0.4f, 0.2f));
    EXPECT_EQ(m.attenuation_distance, 0.25f);
    const Primitive& p = a.meshes.at(0).primitives.at(0);
    ASSERT_EQ(p.tangents.size(), 3u);
    EXPECT_EQ(p.tangents[1], glm::vec4(1, 0, 0, -1));
}

TEST_F(GltfSurface, DefaultsAreNoVolumeAndNoNormalMap) {
    const SceneAsset a = load(triangle(json::object()));
    const Material& m = a.materials.at(0);
    EXPECT_EQ(m.normal_texture, -1);
    EXPECT_EQ(m.thickness, 0.0f);
    EXPECT_EQ(m.attenuation_color, glm::vec3(1.0f));
    EXPECT_EQ(m.attenuation_distance, std::numeric_limits<float>::infinity());
    EXPECT_TRUE(m.base_color_transform.is_identity());
}

TEST_F(GltfSurface, OutOfRangeVolumeValuesAreClampedWithWarnings) {
    const json material = json::parse(R"({"extensions":{"KHR_materials_volume":{
        "thicknessFactor":-2,"attenuationColor":[1.5,-1,0.5],"attenuationDistance":0}}})");
    std::string warnings;
    const Material m = load(triangle(material), &warnings).materials.at(0);
    EXPECT_EQ(m.thickness, 0.0f);
    EXPECT_EQ(m.attenuation_color, glm::vec3(1.0f, 0.0f, 0.5f));
    EXPECT_EQ(m.attenuation_distance, std::numeric_limits<float>::min());
    EXPECT_NE(warnings.find("material 0: thicknessFactor"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("material 0: attenuationColor"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("material 0: attenuationDistance"), std::string::npos) << warnings;
}

TEST_F(GltfSurface, NumbersBeyondAFloatAreRefused) {
    for (const char* bad : {R"({"extensions":{"KHR_materials_volume":{"attenuationDistance":1e39}}})",
                            R"({"normalTexture":{"index":0,"scale":-1e300}})",
                            R"({"normalTexture":{"index":0,"extensions":{"KHR_texture_transform":{"rotation":1e40}}}})"}) {
        SCOPED_TRACE(bad);
        try {
            load(triangle(json::parse(bad)));
            ADD_FAILURE() << "accepted";
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find("does not fit a float"), std::string::npos) << e.what();
        }
    }
}

TEST_F(GltfSurface, ASecondTexCoordSetIsWarnedAboutAndTheTextureIgnored) {
    const json material = json::parse(
        R"({"normalTexture":{"index":0,"extensions":{"KHR_texture_transform":{"texCoord":1}}}})");
    std::string warnings;
    const Material m = load(triangle(material), &warnings).materials.at(0);
    EXPECT_EQ(m.normal_texture, -1);
    EXPECT_NE(warnings.find("normalTexture uses TEXCOORD_1"), std::string::npos) << warnings;
}

TEST_F(GltfSurface, VolumeTransformsAndTangentsSurviveARoundTrip) {
    SceneAsset a = make_builtin_scene("normal_map");
    a.materials[0].base_color_texture = 0;
    a.materials[0].base_color_transform.rotation = -1.0f;
    a.materials[1].transmission = 1.0f;
    a.materials[1].thickness = 2.0f;
    a.materials[1].attenuation_color = {0.1f, 0.2f, 0.3f};
    a.materials[1].attenuation_distance = 7.0f;
    save_gltf(a, file("out.gltf"));
    const SceneAsset b = load_gltf(file("out.gltf"));
    ASSERT_EQ(b.materials.size(), a.materials.size());
    for (std::size_t i = 0; i < a.materials.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(b.materials[i].normal_texture, a.materials[i].normal_texture);
        EXPECT_EQ(b.materials[i].normal_scale, a.materials[i].normal_scale);
        EXPECT_EQ(b.materials[i].normal_transform, a.materials[i].normal_transform);
        EXPECT_EQ(b.materials[i].base_color_transform, a.materials[i].base_color_transform);
        EXPECT_EQ(b.materials[i].thickness, a.materials[i].thickness);
        EXPECT_EQ(b.materials[i].attenuation_color, a.materials[i].attenuation_color);
        EXPECT_EQ(b.materials[i].attenuation_distance, a.materials[i].attenuation_distance);
    }
    EXPECT_EQ(b.meshes[0].primitives[0].tangents, a.meshes[0].primitives[0].tangents);   // the wall's TANGENT
    EXPECT_TRUE(b.meshes[1].primitives[0].tangents.empty());                               // generated, not saved
}

}  // namespace
}  // namespace rt
