// No NaN or Inf pixel for any scene the loader accepts: scenes with the most extreme values glTF files may
// carry (3e38 intensities and strengths, a light touching a surface, indices of refraction at both ends) go through
// load_gltf and flatten, and stage 01's brute-force renderer (the reference every stage is compared with) renders
// them small; every pixel must be finite. kMaxRadiance in light_incidence and surface_coefficients is what holds.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "01_naive/naive_renderer.h"
#include "common/scene/effects.h"
#include "common/scene/gltf/gltf_io.h"
#include "common/trace/shading.h"

namespace rt {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kHuge = 3.0e38;   // fits a float (max 3.4e38), so the loader accepts it

// A floor (two triangles, 4 x 4 at y = 0) and a small tilted quad above it, each with its own material, and the given
// lights on nodes at the given positions. The buffer is embedded as a base64 data URI.
json extreme_scene(const json& floor_material, const json& quad_material, const json& lights,
                   const std::vector<std::array<double, 3>>& light_positions) {
    const float p[] = {-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, -2, 2, 0, 2, -2, 0, 2,    // floor, facing +y
                       -0.5f, 0.5f, 0, 0.5f, 0.5f, 0, 0, 1.2f, -0.3f};               // quad
    std::string bytes(reinterpret_cast<const char*>(p), sizeof p);
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string b64;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {   // sizeof p is a multiple of 3: no padding
        const unsigned v = unsigned(std::uint8_t(bytes[i])) << 16 | unsigned(std::uint8_t(bytes[i + 1])) << 8 |
                           unsigned(std::uint8_t(bytes[i + 2]));
        for (int s = 18; s >= 0; s -= 6) b64 += table[(v >> s) & 63];
    }
    json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"extensionsUsed", {"KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_ior",
                            "KHR_materials_transmission", "KHR_materials_specular"}},
        {"buffers", {{{"uri", "data:application/octet-stream;base64," + b64}, {"byteLength", sizeof p}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteLength", 72}}, {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 36}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 6}, {"type", "VEC3"}},
                       {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"material", 0}}}}},
                    {{"primitives", {{{"attributes", {{"POSITION", 1}}}, {"material", 1}}}}}}},
        {"materials", {floor_material, quad_material}},
        {"extensions", {{"KHR_lights_punctual", {{"lights", lights}}}}},
        {"nodes", {{{"mesh", 0}}, {{"mesh", 1}}}},
        {"scenes", {{{"nodes", {0, 1}}}}},
    };
    for (std::size_t i = 0; i < light_positions.size(); ++i) {
        const auto& at = light_positions[i];
        // Point straight down (-Z turned to -Y) so spot lights face the floor.
        doc["nodes"].push_back({{"translation", {at[0], at[1], at[2]}},
                                {"rotation", {-0.70710678, 0, 0, 0.70710678}},
                                {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
        doc["scenes"][0]["nodes"].push_back(2 + i);
    }
    return doc;
}

struct PixelCheck {
    int non_finite = 0;
    float brightest = 0.0f;   // largest finite channel: shows the extreme value was seen
};

// Loads the document, renders it with stage 01 (all effects, 4 samples per pixel) and checks every pixel.
PixelCheck check_pixels(const json& doc, const std::string& name) {
    const fs::path path = fs::temp_directory_path() /
                          ("rt_extreme_" + name + "_" + std::to_string(std::random_device{}()) + ".gltf");
    std::ofstream(path) << doc.dump();
    SceneAsset asset;
    try {
        asset = load_gltf(path.string());
    } catch (...) {
        fs::remove(path);
        throw;
    }
    fs::remove(path);
    const Scene scene = flatten(asset, FlattenOptions{});
    RenderSettings settings;
    settings.width = 24;
    settings.height = 18;
    settings.spp = 4;
    settings.threads = 2;
    settings.quiet = true;
    settings.effects = resolve_effects("all", scene);
    NaiveRenderer renderer;
    const FrameResult result = renderer.render(scene, settings);
    PixelCheck check;
    for (const glm::vec3& c : result.image.pixels)
        for (int k = 0; k < 3; ++k) {
            if (!std::isfinite(c[k])) ++check.non_finite;
            else check.brightest = std::max(check.brightest, c[k]);
        }
    return check;
}

const json kDiffuse = {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0}}}};
const json kMirror = {{"pbrMetallicRoughness", {{"metallicFactor", 1}, {"roughnessFactor", 0}}}};

TEST(ExtremeValues, HugePointLightTouchingASurfaceGivesFinitePixels) {
    // 3e38 cd at 1e-19 and at 1e-30 above the floor: intensity / d^2 overflows a float many times over.
    const json lights = {{{"type", "point"}, {"intensity", kHuge}}, {{"type", "point"}, {"intensity", kHuge}},
                         {{"type", "spot"}, {"intensity", kHuge}, {"spot", json::object()}}};
    const PixelCheck check =
        check_pixels(extreme_scene(kDiffuse, kMirror, lights, {{0, 1e-19, 0}, {0.3, 1e-30, 0.2}, {0, 0, 0}}), "point");
    EXPECT_EQ(check.non_finite, 0);
    EXPECT_GT(check.brightest, 1.0f);
}

TEST(ExtremeValues, HugeDirectionalLightsAndEmissionGiveFinitePixels) {
    const json glowing = {{"emissiveFactor", {1, 1, 1}},
                          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", kHuge}}}}}};
    json lights = json::array();
    std::vector<std::array<double, 3>> at;
    for (int i = 0; i < 8; ++i) {
        lights.push_back({{"type", "directional"}, {"intensity", kHuge}});
        at.push_back({0, 1, 0});
    }
    json doc = extreme_scene(glowing, kMirror, lights, at);
    doc["scenes"][0]["extras"] = {{"rt_background", {kHuge, kHuge, kHuge}}};   // seen where rays leave the scene
    const PixelCheck check = check_pixels(doc, "directional");
    EXPECT_EQ(check.non_finite, 0);
    // The lights and emission reach kMaxRadiance (1e20) each; the pixel saturates at the one bound of every stage.
    EXPECT_EQ(check.brightest, kMaxSampleRadiance);
}

TEST(ExtremeValues, GlassWithExtremeIorsAndSpecularColourGivesFinitePixels) {
    auto glass = [](double ior, double specular_color) {
        return json{{"pbrMetallicRoughness", {{"metallicFactor", 0}, {"roughnessFactor", 0}}},
                    {"extensions",
                     {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                      {"KHR_materials_ior", {{"ior", ior}}},
                      {"KHR_materials_specular",
                       {{"specularFactor", 1}, {"specularColorFactor", {specular_color, specular_color, 0}}}}}}};
    };
    const json lights = {{{"type", "point"}, {"intensity", kHuge}}};
    const PixelCheck check =
        check_pixels(extreme_scene(glass(kHuge, kHuge), glass(1.0000001, kHuge), lights, {{0, 2, 0}}), "glass");
    EXPECT_EQ(check.non_finite, 0);
    EXPECT_GT(check.brightest, 0.0f);
}

TEST(ExtremeValues, LightIncidenceIsClampedToTheMaximumRadiance) {
    Light light;
    light.intensity = float(kHuge);
    light.position = glm::vec3(0.0f, 1e-20f, 0.0f);
    glm::vec3 to_light;
    float distance;
    const glm::vec3 e = light_incidence(light, glm::vec3(0.0f), glm::vec3(0, 1, 0), to_light, distance);
    for (int c = 0; c < 3; ++c)   // kMaxRadiance times the cosine, about 1 (to_light is rounded at such a distance)
        EXPECT_NEAR(e[c] / kMaxRadiance, 1.0f, 1e-3f);
    Material m;
    m.emissive = glm::vec3(float(kHuge));
    EXPECT_EQ(surface_coefficients(m, glm::vec4(1.0f)).emissive, glm::vec3(kMaxRadiance));
}

}  // namespace
}  // namespace rt
