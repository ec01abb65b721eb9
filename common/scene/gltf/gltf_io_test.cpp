// glTF import/export: round trips of every built-in scene, hand-written files (valid and malformed). How a primitive's
// vertex data is read (topologies, sparse, quantized, morph targets, vertex colours) is gltf_accessors_test.cpp's.
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
#include "gltf_test_support.h"

namespace rt {
namespace {

namespace fs = std::filesystem;
using namespace gltf_test;

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
