// glTF import/export: round trips of every built-in scene, hand-written files (valid and malformed).
// Over 450 lines by choice: loading and saving are tested together because each round trip is a save then a load,
// on the same JSON-writing helpers the load cases use; hostile files have their own file (gltf_hostile_test.cpp).
#include "gltf_io.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"

namespace rt {
namespace {

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

void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::string base64(const std::vector<unsigned char>& data) {
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

std::string data_uri(const std::vector<unsigned char>& bytes) {
    return "data:application/octet-stream;base64," + base64(bytes);
}

// A one-triangle glTF: 3 float positions (36 bytes) then three u16 indices (6 bytes). `indices` and `extra_json`
// let a test break it.
std::string triangle_gltf(const std::vector<std::uint16_t>& indices, const std::string& accessor_count = "3") {
    std::vector<unsigned char> bytes;
    append(bytes, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    append(bytes, indices);
    while (bytes.size() % 4) bytes.push_back(0);
    std::ostringstream s;
    s << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      << R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" << accessor_count
      << R"(,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
      << R"({"bufferView":1,"componentType":5123,"count":)" << indices.size() << R"(,"type":"SCALAR"}],)"
      << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":)"
      << indices.size() * 2 << "}],"
      << R"("buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << data_uri(bytes) << R"("}]})";
    return s.str();
}

void expect_one_line_scene_error(const std::string& path, const std::string& must_contain) {
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

// Flattened scenes must agree exactly on geometry (floats survive the binary buffer bit for bit).
void expect_same_scene(const Scene& a, const Scene& b) {
    ASSERT_EQ(a.triangle_count(), b.triangle_count());
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
        ASSERT_EQ(a.positions[i], b.positions[i]) << "vertex " << i;
        ASSERT_EQ(a.normals[i], b.normals[i]) << "vertex " << i;
        ASSERT_EQ(a.uvs[i], b.uvs[i]) << "vertex " << i;
    }
    EXPECT_EQ(a.material_ids, b.material_ids);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t i = 0; i < a.materials.size(); ++i) {
        const Material &x = a.materials[i], &y = b.materials[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.base_color, y.base_color);
        EXPECT_EQ(x.base_color_texture, y.base_color_texture);
        EXPECT_EQ(x.metallic, y.metallic);
        EXPECT_EQ(x.roughness, y.roughness);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(x.emissive[c], y.emissive[c], 1e-6f * (1 + x.emissive[c]));
        EXPECT_EQ(x.transmission, y.transmission);
        EXPECT_EQ(x.ior, y.ior);
        EXPECT_EQ(x.specular, y.specular);
        EXPECT_EQ(x.specular_color, y.specular_color);
        EXPECT_EQ(x.base_color_texture, y.base_color_texture);
        EXPECT_EQ(x.metallic_roughness_texture, y.metallic_roughness_texture);
        EXPECT_EQ(x.emissive_texture, y.emissive_texture);
        EXPECT_EQ(x.transmission_texture, y.transmission_texture);
        EXPECT_EQ(x.attenuation_color, y.attenuation_color);
        EXPECT_EQ(x.attenuation_distance, y.attenuation_distance);
        EXPECT_EQ(x.thickness, y.thickness);
        EXPECT_EQ(x.normal_texture, y.normal_texture);
        EXPECT_EQ(x.normal_scale, y.normal_scale);
        EXPECT_EQ(x.base_color_transform, y.base_color_transform);
        EXPECT_EQ(x.normal_transform, y.normal_transform);
        EXPECT_EQ(x.alpha_mode, y.alpha_mode);
        EXPECT_EQ(x.alpha_cutoff, y.alpha_cutoff);
    }
    EXPECT_EQ(a.tangents, b.tangents);
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (std::size_t i = 0; i < a.lights.size(); ++i) {
        EXPECT_EQ(a.lights[i].type, b.lights[i].type);
        EXPECT_EQ(a.lights[i].color, b.lights[i].color);
        EXPECT_EQ(a.lights[i].intensity, b.lights[i].intensity);
        EXPECT_EQ(a.lights[i].range, b.lights[i].range);
        EXPECT_EQ(a.lights[i].position, b.lights[i].position);
        EXPECT_EQ(a.lights[i].direction, b.lights[i].direction);
    }
    EXPECT_EQ(a.camera.projection, b.camera.projection);
    EXPECT_EQ(a.camera.yfov, b.camera.yfov);
    EXPECT_EQ(a.camera.aspect, b.camera.aspect);
    EXPECT_EQ(a.camera.znear, b.camera.znear);
    EXPECT_EQ(a.camera.zfar, b.camera.zfar);
    EXPECT_EQ(a.camera.position, b.camera.position);
    EXPECT_EQ(a.camera.forward, b.camera.forward);
    EXPECT_EQ(a.camera.up, b.camera.up);
    EXPECT_EQ(a.default_camera, b.default_camera);
    EXPECT_EQ(a.default_light, b.default_light);
    EXPECT_EQ(a.background, b.background);
    EXPECT_EQ(a.ambient, b.ambient);
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (std::size_t i = 0; i < a.textures.size(); ++i) {
        EXPECT_EQ(a.textures[i].width, b.textures[i].width);
        EXPECT_EQ(a.textures[i].height, b.textures[i].height);
        EXPECT_EQ(a.textures[i].rgba8, b.textures[i].rgba8);
        EXPECT_EQ(a.textures[i].nearest, b.textures[i].nearest);
        EXPECT_EQ(a.textures[i].wrap_s, b.textures[i].wrap_s);
        EXPECT_EQ(a.textures[i].wrap_t, b.textures[i].wrap_t);
    }
}

void expect_round_trip(const SceneAsset& asset, const std::string& path) {
    save_gltf(asset, path);
    std::string warnings;
    const SceneAsset loaded = load_gltf(path, &warnings);
    EXPECT_EQ(warnings, "");
    EXPECT_EQ(loaded.name, fs::path(path).stem().string());
    ASSERT_EQ(loaded.animations.size(), asset.animations.size());
    for (float t : {0.0f, 0.3f, 0.77f, 1.5f, 5.0f}) {
        FlattenOptions options;
        options.time = t;
        expect_same_scene(flatten(asset, options), flatten(loaded, options));
    }
}

// ---------------------------------------------------------------------------------------------------------------

TEST(GltfRoundTrip, EveryBuiltinKeepsTrianglesMaterialsLightsCameraAsGltf) {
    TempDir dir;
    for (std::string name : builtin_scene_names()) {
        if (name == "spheres") name = "spheres:20";
        SCOPED_TRACE(name);
        expect_round_trip(make_builtin_scene(name), dir.file("scene.gltf"));
    }
}

TEST(GltfRoundTrip, EveryBuiltinKeepsTrianglesMaterialsLightsCameraAsGlb) {
    TempDir dir;
    for (std::string name : builtin_scene_names()) {
        if (name == "spheres") name = "spheres:20";
        SCOPED_TRACE(name);
        expect_round_trip(make_builtin_scene(name), dir.file("scene.GLB"));
    }
}

TEST(GltfRoundTrip, SamplerWrapModesAreReadAndWritten) {
    // Every pair of glTF wrap modes (wrapS, wrapT) survives a save and a load; a sampler without them is REPEAT,
    // and a number that is not a wrap mode is REPEAT with a warning.
    TempDir dir;
    SceneAsset a = make_builtin_scene("whitted");
    ASSERT_EQ(a.textures.size(), 1u);
    EXPECT_EQ(a.textures[0].wrap_s, Wrap::Repeat);
    const Wrap modes[] = {Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat};
    for (Wrap s : modes)
        for (Wrap t : modes) {
            a.textures[0].wrap_s = s;
            a.textures[0].wrap_t = t;
            save_gltf(a, dir.file("w.gltf"));
            const SceneAsset b = load_gltf(dir.file("w.gltf"));
            EXPECT_EQ(b.textures[0].wrap_s, s);
            EXPECT_EQ(b.textures[0].wrap_t, t);
        }
    std::ifstream in(dir.file("w.gltf"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find("33648", text.find("\"wrapT\""));   // the last pair: MIRRORED_REPEAT on both
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 5, "12345");
    write_text(dir.file("odd.gltf"), text);
    std::string warnings;
    const SceneAsset odd = load_gltf(dir.file("odd.gltf"), &warnings);
    EXPECT_EQ(odd.textures[0].wrap_t, Wrap::Repeat);
    EXPECT_NE(warnings.find("wrapT 12345 is not a glTF wrap mode; REPEAT"), std::string::npos) << warnings;
}

TEST(GltfRoundTrip, WhittedKeepsTexturePixelsAndNearestSampler) {
    TempDir dir;
    const SceneAsset a = make_builtin_scene("whitted");
    save_gltf(a, dir.file("w.gltf"));
    const SceneAsset b = load_gltf(dir.file("w.gltf"));
    ASSERT_EQ(b.textures.size(), 1u);
    EXPECT_EQ(b.textures[0].rgba8, a.textures[0].rgba8);
    EXPECT_TRUE(b.textures[0].nearest);
    EXPECT_EQ(b.materials[0].base_color_texture, 0);
    // No temporary file is left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(GltfRoundTrip, DynamicKeepsAnimationChannels) {
    TempDir dir;
    const SceneAsset a = make_builtin_scene("dynamic");
    save_gltf(a, dir.file("d.glb"));
    const SceneAsset b = load_gltf(dir.file("d.glb"));
    ASSERT_EQ(b.animations.size(), a.animations.size());
    for (std::size_t i = 0; i < a.animations.size(); ++i) {
        ASSERT_EQ(b.animations[i].channels.size(), a.animations[i].channels.size());
        for (std::size_t c = 0; c < a.animations[i].channels.size(); ++c) {
            const AnimationChannel &x = a.animations[i].channels[c], &y = b.animations[i].channels[c];
            EXPECT_EQ(x.node, y.node);
            EXPECT_EQ(x.path, y.path);
            EXPECT_EQ(x.interpolation, y.interpolation);
            EXPECT_EQ(x.times, y.times);
            EXPECT_EQ(x.values, y.values);
        }
    }
}

TEST(GltfRoundTrip, KeepsExtensionMaterialsSpotDirectionalAndOrthographic) {
    TempDir dir;
    SceneAsset a;
    a.name = "x";
    Material m;
    m.name = "glow";
    m.base_color = {0.2f, 0.4f, 0.6f, 0.8f};
    m.metallic = 0.25f;
    m.roughness = 0.5f;
    m.emissive = {5.0f, 2.5f, 0.0f};
    m.transmission = 0.5f;
    m.ior = 1.33f;
    m.specular = 0.7f;
    m.specular_color = {0.9f, 0.8f, 0.7f};
    m.metallic_roughness_texture = 0;
    m.emissive_texture = 1;
    m.transmission_texture = 1;
    a.materials.push_back(m);
    for (int i = 0; i < 2; ++i) {
        Texture t;
        t.width = 2;
        t.height = 1;
        t.rgba8 = {0, std::uint8_t(40 * i), 255, 255, 9, 99, 199, 255};
        a.textures.push_back(t);
    }
    Mesh mesh;
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.material = 0;
    mesh.primitives.push_back(p);
    a.meshes.push_back(mesh);
    Light spot;
    spot.type = LightType::Spot;
    spot.color = {1, 0.5f, 0.25f};
    spot.intensity = 12;
    spot.range = 30;
    spot.inner_cone = 0.2f;
    spot.outer_cone = 0.5f;
    Light sun;
    sun.type = LightType::Directional;
    sun.intensity = 3;
    a.lights = {spot, sun};
    Camera ortho;
    ortho.projection = Projection::Orthographic;
    ortho.xmag = 2;
    ortho.ymag = 1.5f;
    ortho.znear = 0.1f;
    ortho.zfar = 100;
    a.cameras.push_back(ortho);
    Node n0, n1, n2, n3;
    n0.mesh = 0;
    n1.light = 0;
    n1.translation = {1, 2, 3};
    n1.rotation = glm::angleAxis(0.3f, glm::normalize(glm::vec3(1, 2, 3)));
    n2.light = 1;
    n2.matrix = glm::mat4(2.0f);
    (*n2.matrix)[3] = glm::vec4(4, 5, 6, 1);
    n3.camera = 0;
    n3.scale = {2, 2, 2};
    a.nodes = {n0, n1, n2, n3};
    a.roots = {0, 1, 2, 3};
    a.background = {0.1f, 0.2f, 0.3f};
    save_gltf(a, dir.file("x.gltf"));

    std::ifstream in(dir.file("x.gltf"));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* ext : {"KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior",
                            "KHR_materials_specular", "KHR_lights_punctual", "extensionsUsed"})
        EXPECT_NE(text.find(ext), std::string::npos) << ext;

    const SceneAsset b = load_gltf(dir.file("x.gltf"));
    ASSERT_EQ(b.materials.size(), 1u);
    EXPECT_EQ(b.materials[0].base_color, m.base_color);
    EXPECT_NEAR(b.materials[0].emissive.x, 5.0f, 1e-5f);
    EXPECT_NEAR(b.materials[0].emissive.y, 2.5f, 1e-5f);
    EXPECT_EQ(b.materials[0].ior, 1.33f);
    EXPECT_EQ(b.materials[0].specular_color, m.specular_color);
    ASSERT_EQ(b.lights.size(), 2u);
    EXPECT_EQ(b.lights[0].type, LightType::Spot);
    EXPECT_EQ(b.lights[0].inner_cone, 0.2f);
    EXPECT_EQ(b.lights[0].outer_cone, 0.5f);
    EXPECT_EQ(b.lights[0].range, 30.0f);
    EXPECT_EQ(b.lights[1].type, LightType::Directional);
    ASSERT_EQ(b.cameras.size(), 1u);
    EXPECT_EQ(b.cameras[0].projection, Projection::Orthographic);
    EXPECT_EQ(b.cameras[0].xmag, 2.0f);
    EXPECT_EQ(b.cameras[0].ymag, 1.5f);
    ASSERT_TRUE(b.nodes[2].matrix.has_value());
    EXPECT_EQ(*b.nodes[2].matrix, *n2.matrix);
    EXPECT_EQ(b.background, a.background);
    expect_same_scene(flatten(a, {}), flatten(b, {}));
}

TEST(GltfRoundTrip, NonIndexedPrimitiveStaysNonIndexed) {
    TempDir dir;
    SceneAsset a;
    Mesh mesh;
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    p.uvs = {{0, 0}, {1, 0}, {0, 1}, {0.25f, 0}, {1, 0.5f}, {0, 0.75f}};
    mesh.primitives.push_back(p);
    a.meshes.push_back(mesh);
    Node n;
    n.mesh = 0;
    a.nodes.push_back(n);
    a.roots = {0};
    save_gltf(a, dir.file("n.gltf"));
    const SceneAsset b = load_gltf(dir.file("n.gltf"));
    ASSERT_EQ(b.meshes.size(), 1u);
    EXPECT_TRUE(b.meshes[0].primitives[0].indices.empty());
    EXPECT_TRUE(b.meshes[0].primitives[0].normals.empty());
    EXPECT_EQ(b.meshes[0].primitives[0].material, -1);
    expect_same_scene(flatten(a, {}), flatten(b, {}));
}

// ---------------------------------------------------------------------------------------------------------------

TEST(GltfLoad, HandWrittenTriangleLoads) {
    TempDir dir;
    write_text(dir.file("t.gltf"), triangle_gltf({0, 1, 2}));
    const SceneAsset a = load_gltf(dir.file("t.gltf"));
    EXPECT_EQ(a.name, "t");
    ASSERT_EQ(a.meshes.size(), 1u);
    EXPECT_EQ(a.meshes[0].primitives[0].indices, (std::vector<std::uint32_t>{0, 1, 2}));
    const Scene s = flatten(a, {});
    ASSERT_EQ(s.triangle_count(), 1u);
    // No normals in the file: the flat face normal (+Z for this counter-clockwise triangle).
    EXPECT_EQ(s.normals[0], glm::vec3(0, 0, 1));
    EXPECT_TRUE(s.default_camera);
    EXPECT_TRUE(s.default_light);
    // A glTF file says nothing of its world or of ambient light: the default world and the hemisphere ambient.
    EXPECT_FALSE(a.has_world);
    EXPECT_EQ(a.ambient, AmbientModel::Hemisphere);
}

// Our extras survive a round trip: a scene with a background keeps it and its ambient model; one without a world
// (a glTF file read and written again) is written without rt_background, so it gets the default world again.
TEST(GltfRoundTrip, WorldAndAmbientSurviveAndAFileWithoutAWorldStaysWithout) {
    TempDir dir;
    write_text(dir.file("t.gltf"), triangle_gltf({0, 1, 2}));
    SceneAsset a = load_gltf(dir.file("t.gltf"));
    save_gltf(a, dir.file("again.gltf"));
    const SceneAsset b = load_gltf(dir.file("again.gltf"));
    EXPECT_FALSE(b.has_world);
    EXPECT_EQ(b.ambient, AmbientModel::Hemisphere);
    for (AmbientModel model : {AmbientModel::None, AmbientModel::Constant, AmbientModel::Hemisphere}) {
        a.has_world = true;
        a.background = glm::vec3(0.25f, 0.5f, 1.0f);
        a.ambient = model;
        save_gltf(a, dir.file("world.gltf"));
        const SceneAsset c = load_gltf(dir.file("world.gltf"));
        EXPECT_TRUE(c.has_world);
        EXPECT_EQ(c.background, a.background);
        EXPECT_EQ(c.ambient, model);
    }
}

TEST(GltfLoad, UnknownAmbientExtraIsRefusedInOneLine) {
    TempDir dir;
    std::string text = triangle_gltf({0, 1, 2});
    const std::string scenes = R"("scenes":[{"nodes":[0]}])";
    text.replace(text.find(scenes), scenes.size(), R"("scenes":[{"nodes":[0],"extras":{"rt_ambient":"shiny"}}])");
    write_text(dir.file("a.gltf"), text);
    expect_one_line_scene_error(dir.file("a.gltf"), "rt_ambient is not one of none, constant or hemisphere");
}

TEST(GltfLoad, MissingFileThrowsOneLineSceneError) {
    TempDir dir;
    expect_one_line_scene_error(dir.file("nope.gltf"), "no such file");
    expect_one_line_scene_error(dir.file("nope.glb"), "no such file");
}

TEST(GltfLoad, UnknownExtensionThrowsSceneError) {
    TempDir dir;
    write_text(dir.file("scene.obj"), "o x\n");
    expect_one_line_scene_error(dir.file("scene.obj"), "extension");
}

TEST(GltfLoad, MalformedJsonThrowsOneLineSceneError) {
    TempDir dir;
    write_text(dir.file("bad.gltf"), "{\"asset\": {\"version\": \"2.0\"},\n \"nodes\": [ {\"mesh\": 0 \n");
    expect_one_line_scene_error(dir.file("bad.gltf"), "");
    write_text(dir.file("empty.gltf"), "");
    expect_one_line_scene_error(dir.file("empty.gltf"), "");
    write_text(dir.file("array.gltf"), "[1, 2, 3]");
    expect_one_line_scene_error(dir.file("array.gltf"), "");
}

TEST(GltfLoad, GarbageGlbThrowsOneLineSceneError) {
    TempDir dir;
    write_text(dir.file("bad.glb"), "glTF\x02\x00\x00\x00garbage that is not a chunk");
    expect_one_line_scene_error(dir.file("bad.glb"), "");
    // A valid file cut in half.
    save_gltf(make_builtin_scene("diffuse"), dir.file("ok.glb"));
    std::ifstream in(dir.file("ok.glb"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    write_text(dir.file("cut.glb"), bytes.substr(0, bytes.size() / 2));
    expect_one_line_scene_error(dir.file("cut.glb"), "");
}

TEST(GltfLoad, OutOfRangeIndexThrowsOneLineSceneError) {
    TempDir dir;
    write_text(dir.file("t.gltf"), triangle_gltf({0, 1, 7}));
    expect_one_line_scene_error(dir.file("t.gltf"), "index 7 out of range");
}

TEST(GltfLoad, AccessorPastItsBufferViewThrowsSceneError) {
    TempDir dir;
    write_text(dir.file("t.gltf"), triangle_gltf({0, 1, 2}, "1000"));
    expect_one_line_scene_error(dir.file("t.gltf"), "accessor 0");
    write_text(dir.file("huge.gltf"), triangle_gltf({0, 1, 2}, "4294967295"));
    expect_one_line_scene_error(dir.file("huge.gltf"), "");
}

TEST(GltfLoad, BadReferencesThrowSceneError) {
    TempDir dir;
    std::string text = triangle_gltf({0, 1, 2});
    // A node pointing at a mesh that does not exist.
    std::string bad_mesh = text;
    bad_mesh.replace(bad_mesh.find("{\"mesh\":0}"), 10, "{\"mesh\":5}");
    write_text(dir.file("m.gltf"), bad_mesh);
    expect_one_line_scene_error(dir.file("m.gltf"), "mesh");
    // A node that is its own child.
    std::string cycle = text;
    cycle.replace(cycle.find("{\"mesh\":0}"), 10, "{\"mesh\":0,\"children\":[0]}");
    write_text(dir.file("c.gltf"), cycle);
    expect_one_line_scene_error(dir.file("c.gltf"), "");
    // A material that does not exist.
    std::string bad_material = text;
    bad_material.replace(bad_material.find("\"indices\":1"), 11, "\"indices\":1,\"material\":3");
    write_text(dir.file("mat.gltf"), bad_material);
    expect_one_line_scene_error(dir.file("mat.gltf"), "material");
}

TEST(GltfLoad, TriangleStripAndFanAreReadAsTheTrianglesTheyStandFor) {
    // A unit quad in z = 0 facing +z, as a strip of its 4 vertices in order (0 1 2 3: a zigzag) and as a fan over
    // indices (0 1 3 2: around it). glTF 2.0 3.7.2.1: strip triangles {0,1,2}, {1,3,2}; fan {1,3,0}, {3,2,0}.
    TempDir dir;
    std::vector<unsigned char> bytes;
    append(bytes, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
    append(bytes, std::vector<std::uint16_t>{0, 1, 3, 2});
    std::ostringstream s;
    s << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":5},)"
      << R"({"attributes":{"POSITION":0},"indices":1,"mode":6}]}],)"
      << R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},)"
      << R"({"bufferView":1,"componentType":5123,"count":4,"type":"SCALAR"}],)"
      << R"("bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":8}],)"
      << R"("buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << data_uri(bytes) << R"("}]})";
    write_text(dir.file("s.gltf"), s.str());
    std::string warnings;
    const SceneAsset a = load_gltf(dir.file("s.gltf"), &warnings);
    EXPECT_EQ(warnings, "");
    ASSERT_EQ(a.meshes[0].primitives.size(), 2u);
    EXPECT_EQ(a.meshes[0].primitives[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
    EXPECT_EQ(a.meshes[0].primitives[1].indices, (std::vector<std::uint32_t>{1, 3, 0, 3, 2, 0}));
    const Scene scene = flatten(a, {});
    ASSERT_EQ(scene.triangle_count(), 4u);
    // Too few indices for a triangle: none (not the vertices in order, which an empty index list would mean), in a
    // fan as in a plain list.
    for (const char* mode : {"6", "4"}) {
        std::string two = s.str();
        two.replace(two.find(R"("count":4,"type":"SCALAR")"), 9, R"("count":2)");
        two.replace(two.find(R"("mode":6)"), 8, std::string(R"("mode":)") + mode);
        write_text(dir.file("two.gltf"), two);
        EXPECT_EQ(flatten(load_gltf(dir.file("two.gltf")), {}).triangle_count(), 2u) << mode;   // the strip's two
    }
    for (std::size_t t = 0; t < 4; ++t) {   // every triangle keeps the quad's winding: its normal is +z
        const glm::vec3 p0 = scene.positions[3 * t], p1 = scene.positions[3 * t + 1], p2 = scene.positions[3 * t + 2];
        EXPECT_GT(glm::cross(p1 - p0, p2 - p0).z, 0.0f) << "triangle " << t;
    }
}

// A sparse accessor (glTF 2.0, 3.6.2.3) over a triangle's POSITION: its dense part is the buffer view's, or zeros
// without one, and `count` substitutions replace elements. The glTF text for one case.
std::string sparse_triangle_gltf(const std::string& accessor_base, const std::string& sparse) {
    std::vector<unsigned char> bytes;
    append(bytes, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});   // 0..35: the dense positions
    append(bytes, std::vector<std::uint16_t>{1, 2});                // 36..39: substitution indices
    append(bytes, std::vector<float>{5, 0, 0, 0, 5, 0});            // 40..63: their values
    std::ostringstream s;
    s << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
      << R"("accessors":[{)" << accessor_base << R"("componentType":5126,"count":3,"type":"VEC3","sparse":)" << sparse
      << R"(}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":4},)"
      << R"({"buffer":0,"byteOffset":40,"byteLength":24}],)"
      << R"("buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << data_uri(bytes) << R"("}]})";
    return s.str();
}

TEST(GltfLoad, SparseAccessorReplacesItsElementsOverTheBufferViewOrZeros) {
    TempDir dir;
    const std::string two = R"({"count":2,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2}})";
    write_text(dir.file("dense.gltf"), sparse_triangle_gltf(R"("bufferView":0,)", two));
    const std::vector<glm::vec3> over_dense = load_gltf(dir.file("dense.gltf")).meshes[0].primitives[0].positions;
    EXPECT_EQ(over_dense, (std::vector<glm::vec3>{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}));
    write_text(dir.file("zeros.gltf"), sparse_triangle_gltf("", two));   // no bufferView: the dense part is zeros
    EXPECT_EQ(load_gltf(dir.file("zeros.gltf")).meshes[0].primitives[0].positions, over_dense);
    std::string no_sparse = sparse_triangle_gltf("", two);   // neither: all zeros, a valid (if empty) triangle
    const std::string sparse_member = ",\"sparse\":" + two;
    no_sparse.erase(no_sparse.find(sparse_member), sparse_member.size());
    write_text(dir.file("none.gltf"), no_sparse);
    EXPECT_EQ(load_gltf(dir.file("none.gltf")).meshes[0].primitives[0].positions, std::vector<glm::vec3>(3));
    const std::string one = R"({"count":1,"indices":{"bufferView":1,"byteOffset":2,"componentType":5123},)"
                            R"("values":{"bufferView":2,"byteOffset":12}})";   // element 2 only
    write_text(dir.file("one.gltf"), sparse_triangle_gltf(R"("bufferView":0,)", one));
    EXPECT_EQ(load_gltf(dir.file("one.gltf")).meshes[0].primitives[0].positions,
              (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 5, 0}}));
}

TEST(GltfLoad, SparseAccessorOutOfItsRangeOrOrderOrBuffersIsRefused) {
    TempDir dir;
    auto refused = [&](const std::string& sparse, const std::string& expected) {
        write_text(dir.file("s.gltf"), sparse_triangle_gltf(R"("bufferView":0,)", sparse));
        expect_one_line_scene_error(dir.file("s.gltf"), expected);
    };
    refused(R"({"count":4,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2}})",
            "count 4 is not from 1 to the accessor's count");
    refused(R"({"count":2,"indices":{"bufferView":1,"componentType":5126},"values":{"bufferView":2}})",
            "indices must be unsigned byte, short or int");
    refused(R"({"count":2,"indices":{"bufferView":1,"componentType":5121},"values":{"bufferView":2}})",
            "is not increasing and below the count");   // the bytes 1, 0, 2, 0 as u8: 1 then 0
    refused(R"({"count":2,"indices":{"bufferView":1,"byteOffset":2,"componentType":5123},"values":{"bufferView":2}})",
            "data exceeds its bufferView");
    refused(R"({"count":2,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2,"byteOffset":-4}})",
            "");
    refused(R"({"count":2,"indices":{"bufferView":9,"componentType":5123},"values":{"bufferView":2}})", "");
}

TEST(GltfLoad, AccessorsWithoutABufferViewPastTheirBudgetAreRefusedBeforeAllocating) {
    // A few bytes of JSON asking for 2^24 + 1 zero positions: refused, not 256 MiB allocated and rendered.
    TempDir dir;
    std::string text = sparse_triangle_gltf(
        "", R"({"count":2,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":2}})");
    text.replace(text.find("\"count\":3"), 9, "\"count\":16777217");
    write_text(dir.file("z.gltf"), text);
    expect_one_line_scene_error(dir.file("z.gltf"), "without a bufferView add up to more than 16777216 elements");
}

TEST(GltfLoad, QuantizedAttributesAreReadWithKhrMeshQuantizationAndRefusedWithoutIt) {
    // KHR_mesh_quantization: SHORT positions (not normalized: their values, scaled back by the node), BYTE normalized
    // normals, UNSIGNED_SHORT texture coordinates (not normalized). Every element is 4-byte aligned (3.6.2.4).
    TempDir dir;
    std::vector<unsigned char> bytes;
    append(bytes, std::vector<std::int16_t>{0, 0, 0, 0, 200, 0, 0, 0, 0, 200, 0, 0});   // 3 x (x, y, z, pad)
    append(bytes, std::vector<std::int8_t>{0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0});  // 3 x (+z, pad)
    append(bytes, std::vector<std::uint16_t>{0, 0, 3, 0, 0, 5});
    auto gltf = [&](const std::string& extensions) {
        std::ostringstream s;
        s << R"({"asset":{"version":"2.0"},)" << extensions << R"("nodes":[{"mesh":0,"scale":[0.01,0.01,0.01]}],)"
          << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}}]}],)"
          << R"("accessors":[{"bufferView":0,"componentType":5122,"count":3,"type":"VEC3"},)"
          << R"({"bufferView":1,"componentType":5120,"normalized":true,"count":3,"type":"VEC3"},)"
          << R"({"bufferView":2,"componentType":5123,"count":3,"type":"VEC2"}],)"
          << R"("bufferViews":[{"buffer":0,"byteLength":24,"byteStride":8},)"
          << R"({"buffer":0,"byteOffset":24,"byteLength":12,"byteStride":4},)"
          << R"({"buffer":0,"byteOffset":36,"byteLength":12}],)"
          << R"("buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << data_uri(bytes) << R"("}]})";
        return s.str();
    };
    write_text(dir.file("q.gltf"),
               gltf(R"("extensionsUsed":["KHR_mesh_quantization"],"extensionsRequired":["KHR_mesh_quantization"],)"));
    std::string warnings;
    const SceneAsset a = load_gltf(dir.file("q.gltf"), &warnings);
    EXPECT_EQ(warnings, "");   // a supported extension: no "does not implement" line
    const Primitive& p = a.meshes[0].primitives[0];
    EXPECT_EQ(p.positions, (std::vector<glm::vec3>{{0, 0, 0}, {200, 0, 0}, {0, 200, 0}}));
    EXPECT_EQ(p.normals, (std::vector<glm::vec3>(3, {0, 0, 1})));
    EXPECT_EQ(p.uvs, (std::vector<glm::vec2>{{0, 0}, {3, 0}, {0, 5}}));
    const Scene scene = flatten(a, {});
    EXPECT_EQ(scene.positions[1], glm::vec3(2, 0, 0));
    write_text(dir.file("plain.gltf"), gltf(""));   // the same types without the extension: not glTF 2.0
    expect_one_line_scene_error(dir.file("plain.gltf"), "POSITION (accessor 0): unsupported component type");
}

TEST(GltfLoad, MorphTargetsApplyAtTheMeshDefaultWeights) {
    // A triangle with one target moving every vertex by (0, 0, 2) and tilting its normals, at weight 0.5 (glTF 2.0,
    // 3.7.2.2); weight 0 leaves the base. A node's own weights are warned of (not read).
    TempDir dir;
    std::vector<unsigned char> bytes;
    append(bytes, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});   // 0: positions
    append(bytes, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1});   // 36: normals
    append(bytes, std::vector<float>{0, 0, 2, 0, 0, 2, 0, 0, 2});   // 72: target positions
    append(bytes, std::vector<float>{2, 0, 0, 2, 0, 0, 2, 0, 0});   // 108: target normals
    auto gltf = [&](const std::string& weights) {
        std::ostringstream s;
        s << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0},{"mesh":0,"weights":[0.25]}],)"
          << R"("meshes":[{"weights":[)" << weights << R"(],)"
          << R"("primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"COLOR_0":1},"targets":[{"POSITION":2,)"
          << R"("NORMAL":3}]},{"attributes":{"POSITION":0,"COLOR_0":1},"targets":[{"POSITION":2}]}]}],)"
          << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
          << R"({"bufferView":0,"byteOffset":36,"componentType":5126,"count":3,"type":"VEC3"},)"
          << R"({"bufferView":0,"byteOffset":72,"componentType":5126,"count":3,"type":"VEC3"},)"
          << R"({"bufferView":0,"byteOffset":108,"componentType":5126,"count":3,"type":"VEC3"}],)"
          << R"("bufferViews":[{"buffer":0,"byteLength":144}],)"
          << R"("buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << data_uri(bytes) << R"("}]})";
        return s.str();
    };
    write_text(dir.file("half.gltf"), gltf("0.5"));
    std::string warnings;
    const SceneAsset a = load_gltf(dir.file("half.gltf"), &warnings);
    EXPECT_EQ(a.meshes[0].primitives[0].positions, (std::vector<glm::vec3>{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}));
    EXPECT_EQ(a.meshes[0].primitives[0].normals, (std::vector<glm::vec3>(3, {1, 0, 1})));
    EXPECT_EQ(a.meshes[0].primitives[1].positions, a.meshes[0].primitives[0].positions);
    EXPECT_EQ(a.meshes[0].primitives[0].colors, (std::vector<glm::vec4>(3, {0, 0, 1, 1})));   // COLOR_0 as RGB
    EXPECT_NE(warnings.find("node 1: its own morph target weights are not read"), std::string::npos) << warnings;
    EXPECT_EQ(flatten(a, {}).normals[0], glm::normalize(glm::vec3(1, 0, 1)));
    write_text(dir.file("zero.gltf"), gltf("0"));
    EXPECT_EQ(load_gltf(dir.file("zero.gltf")).meshes[0].primitives[0].positions,
              (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    write_text(dir.file("nan.gltf"), gltf("1e39"));   // a weight must fit a float, like every number read
    expect_one_line_scene_error(dir.file("nan.gltf"), "weight 0 is 1e+39, which does not fit a float");
}

TEST(GltfLoad, VertexColoursAreReadClampedAndFlattenedWithWhiteForPrimitivesWithout) {
    // COLOR_0 as normalized RGBA bytes on one primitive (glTF 2.0, 3.7.2.1), none on the other; and as floats.
    TempDir dir;
    std::vector<unsigned char> bytes;
    append(bytes, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});                  // 0: positions
    append(bytes, std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 51, 0, 0, 255, 0});   // 36: RGBA bytes
    append(bytes, std::vector<float>{2, 0.5f, 0, 0.25f, 0.5f, 0, 0, 0.5f, -1});     // 48: floats, some outside [0, 1]
    auto gltf = [&](const std::string& colour_accessor) {
        std::ostringstream s;
        s << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0}],"meshes":[{"primitives":[)"
          << R"({"attributes":{"POSITION":0,"COLOR_0":1}},{"attributes":{"POSITION":0}}]}],)"
          << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)" << colour_accessor
          << R"(],"bufferViews":[{"buffer":0,"byteLength":84}],)"
          << R"("buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << data_uri(bytes) << R"("}]})";
        return s.str();
    };
    write_text(dir.file("bytes.gltf"), gltf(R"({"bufferView":0,"byteOffset":36,"componentType":5121,)"
                                            R"("normalized":true,"count":3,"type":"VEC4"})"));
    std::string warnings;
    const SceneAsset a = load_gltf(dir.file("bytes.gltf"), &warnings);
    EXPECT_EQ(warnings, "");
    EXPECT_EQ(a.meshes[0].primitives[0].colors,
              (std::vector<glm::vec4>{{1, 0, 0, 1}, {0, 1, 0, 0.2f}, {0, 0, 1, 0}}));
    EXPECT_TRUE(a.meshes[0].primitives[1].colors.empty());
    const Scene scene = flatten(a, {});
    ASSERT_EQ(scene.colors.size(), 6u);   // per vertex, white for the primitive without COLOR_0
    EXPECT_EQ(scene.colors[1], glm::vec4(0, 1, 0, 0.2f));
    EXPECT_EQ(scene.colors[4], glm::vec4(1.0f));
    EXPECT_TRUE(analyze_effects(scene).textures);   // a varying base colour, like a texture
    EXPECT_TRUE(flatten(make_builtin_scene("cornell"), {}).colors.empty());   // no COLOR_0: no colours, no bytes

    write_text(dir.file("floats.gltf"),
               gltf(R"({"bufferView":0,"byteOffset":48,"componentType":5126,"count":3,"type":"VEC3"})"));
    warnings.clear();
    const SceneAsset b = load_gltf(dir.file("floats.gltf"), &warnings);
    EXPECT_EQ(b.meshes[0].primitives[0].colors,
              (std::vector<glm::vec4>{{1, 0.5f, 0, 1}, {0.25f, 0.5f, 0, 1}, {0, 0.5f, 0, 1}}));
    EXPECT_NE(warnings.find("COLOR_0 values outside [0, 1]; clamped"), std::string::npos) << warnings;

    // Exported and read back: the same colours (as float RGBA).
    save_gltf(a, dir.file("out.gltf"));
    EXPECT_EQ(load_gltf(dir.file("out.gltf")).meshes[0].primitives[0].colors, a.meshes[0].primitives[0].colors);
}

TEST(GltfLoad, InterleavedStrideAndByteIndicesAndPointsSkipped) {
    TempDir dir;
    // Interleaved position + normal (byteStride 24), u8 indices, plus a POINTS primitive that must be skipped.
    std::vector<unsigned char> bytes;
    append(bytes, std::vector<float>{0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, 1, 0, 2, 0, 0, 0, 1});
    append(bytes, std::vector<std::uint8_t>{0, 1, 2, 0});
    std::ostringstream s;
    s << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0,"translation":[0,0,-1]}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2},)"
      << R"({"attributes":{"POSITION":0},"mode":0}]}],)"
      << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
      << R"({"bufferView":0,"byteOffset":12,"componentType":5126,"count":3,"type":"VEC3"},)"
      << R"({"bufferView":1,"componentType":5121,"count":3,"type":"SCALAR"}],)"
      << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":72,"byteStride":24},)"
      << R"({"buffer":0,"byteOffset":72,"byteLength":3}],)"
      << R"("buffers":[{"byteLength":)" << bytes.size() << R"(,"uri":")" << data_uri(bytes) << R"("}]})";
    write_text(dir.file("i.gltf"), s.str());
    std::string warnings;
    const SceneAsset a = load_gltf(dir.file("i.gltf"), &warnings);
    EXPECT_NE(warnings.find("mode 0 is points or lines, not triangles; skipped"), std::string::npos) << warnings;
    ASSERT_EQ(a.meshes[0].primitives.size(), 1u);   // no scenes: every parentless node is a root
    EXPECT_EQ(a.roots, std::vector<int>{0});
    const Primitive& p = a.meshes[0].primitives[0];
    EXPECT_EQ(p.positions[1], glm::vec3(2, 0, 0));
    EXPECT_EQ(p.positions[2], glm::vec3(0, 2, 0));
    EXPECT_EQ(p.normals[2], glm::vec3(0, 0, 1));
    const Scene scene = flatten(a, {});
    ASSERT_EQ(scene.triangle_count(), 1u);
    EXPECT_EQ(scene.positions[1], glm::vec3(2, 0, -1));
}

TEST(GltfSave, BadExtensionOrFolderThrowsSceneError) {
    TempDir dir;
    const SceneAsset a = make_builtin_scene("diffuse");
    EXPECT_THROW(save_gltf(a, dir.file("scene.obj")), SceneError);
    EXPECT_THROW(save_gltf(a, dir.file("no/such/folder/scene.gltf")), SceneError);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(GltfSave, InconsistentTextureThrowsSceneError) {
    TempDir dir;
    SceneAsset a;
    Texture t;
    t.width = 4;
    t.height = 4;
    t.rgba8.resize(3);
    a.textures.push_back(t);
    EXPECT_THROW(save_gltf(a, dir.file("t.gltf")), SceneError);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace rt
