// Hostile glTF input, one test per class: crashes and hangs (deep hierarchies, deep JSON, URIs naming
// things that are not files), the triangle budget, malformed glTF that tinygltf alone accepts, and values that do
// not fit a float. Every refusal is a one-line SceneError naming the file.
#include "gltf_io.h"
#include "gltf_test_support.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

namespace rt {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class GltfHostile : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("rt_hostile_" + std::string(info->name()) + "_" +
                                            std::to_string(std::random_device{}()));
        fs::create_directories(dir_);
        // The triangle's buffer: three float positions, kept in a file so URIs can be pointed elsewhere.
        const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        std::ofstream(file("tri.bin"), std::ios::binary).write(reinterpret_cast<const char*>(positions), 36);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    std::string file(const std::string& name) const { return (dir_ / name).string(); }

    // A valid one-triangle scene whose buffer is tri.bin.
    static json triangle() {
        return json::parse(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
            "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
            "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
            "bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"uri":"tri.bin","byteLength":36}]})");
    }

    std::string write(const std::string& text, const std::string& name = "scene.gltf") const {
        std::ofstream(file(name), std::ios::binary) << text;
        return file(name);
    }
    std::string write(const json& doc) const { return write(doc.dump()); }

    // Loads and expects a one-line SceneError naming the file and containing `expected`.
    void expect_refused(const std::string& path, const std::string& expected) const {
        try {
            load_gltf(path);
            ADD_FAILURE() << "accepted; expected an error containing '" << expected << "'";
        } catch (const SceneError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(path), std::string::npos) << message;
            EXPECT_NE(message.find(expected), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            EXPECT_LT(message.size(), 400u) << message;
        }
    }
    void expect_refused(const json& doc, const std::string& expected) const { expect_refused(write(doc), expected); }

    fs::path dir_;
};

// ---------------------------------------------------------------------------------------------------------------
// Crashes and hangs.

TEST_F(GltfHostile, NodeChainHundredThousandDeepLoadsAndFlattensWithoutStackOverflow) {
    constexpr int depth = 100'000;
    json doc = triangle();
    doc["nodes"] = json::array();
    for (int i = 0; i < depth; ++i) {
        json node = {{"translation", {0.0, 0.0, 1e-6}}};
        if (i + 1 < depth) node["children"] = {i + 1};
        else node["mesh"] = 0;
        doc["nodes"].push_back(node);
    }
    const SceneAsset asset = load_gltf(write(doc));
    ASSERT_EQ(asset.nodes.size(), std::size_t(depth));
    const Scene scene = flatten(asset, FlattenOptions{});
    EXPECT_EQ(scene.triangle_count(), 1u);
    EXPECT_NEAR(scene.positions[0].z, depth * 1e-6f, 1e-3f);
}

TEST_F(GltfHostile, JsonNestedDeeperThanTheLimitIsRefusedBeforeParsing) {
    const int depth = 100'000;
    json doc = triangle();
    std::string text = doc.dump();
    text.pop_back();   // reopen the root object and add deeply nested extras
    text += R"(,"extras":)" + std::string(depth, '[') + std::string(depth, ']') + "}";
    expect_refused(write(text), "nests deeper than 512");
}

TEST_F(GltfHostile, BracketsInsideStringsDoNotCountAsNesting) {
    json doc = triangle();
    doc["asset"]["generator"] = std::string(2000, '[');
    EXPECT_EQ(load_gltf(write(doc)).meshes.size(), 1u);
}

TEST_F(GltfHostile, GlbWithDeeplyNestedJsonChunkIsRefused) {
    std::string chunk =
        R"({"asset":{"version":"2.0"},"extras":)" + std::string(5000, '[') + std::string(5000, ']') + "}";
    while (chunk.size() % 4) chunk += ' ';
    std::string glb = "glTF";
    auto u32 = [&](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(std::uint32_t(12 + 8 + chunk.size()));
    u32(std::uint32_t(chunk.size()));
    glb += "JSON" + chunk;
    expect_refused(write(glb, "deep.glb"), "nests deeper than 512");
}

TEST_F(GltfHostile, BufferUriNamingAFifoIsRefusedWithoutBlocking) {
    ASSERT_EQ(::mkfifo(file("pipe.bin").c_str(), 0600), 0);
    json doc = triangle();
    doc["buffers"][0]["uri"] = "pipe.bin";
    const auto start = std::chrono::steady_clock::now();
    expect_refused(doc, "pipe.bin': is a FIFO");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST_F(GltfHostile, BufferUriNamingAFolderADeviceOrNothingIsRefused) {
    fs::create_directories(file("folder.bin"));
    json doc = triangle();
    doc["buffers"][0]["uri"] = "folder.bin";
    expect_refused(doc, "folder.bin': is a folder");
    doc["buffers"][0]["uri"] = "missing.bin";
    expect_refused(doc, "missing.bin': no such file");
    fs::create_symlink("/dev/zero", file("zero.bin"));   // URIs are relative: reach the device through a link
    doc["buffers"][0]["uri"] = "zero.bin";
    expect_refused(doc, "zero.bin': is a device");
}

TEST_F(GltfHostile, ImageUriNamingAFolderIsRefused) {
    fs::create_directories(file("picture.png"));
    json doc = triangle();
    doc["images"] = {{{"uri", "picture.png"}}};
    expect_refused(doc, "picture.png': is a folder");
}

TEST_F(GltfHostile, ImageLargerThanTheLimitIsRefusedBeforeDecoding) {
    // Only a PNG signature and IHDR claiming 20000 x 100 pixels: refused from the header, never decoded.
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string("\0\0\0\x0dIHDR", 8);
    png += std::string("\0\0\x4e\x20\0\0\0\x64", 8);   // big-endian 20000, 100
    png += std::string(17, '\0');
    std::ofstream(file("big.png"), std::ios::binary) << png;
    json doc = triangle();
    doc["images"] = {{{"uri", "big.png"}}};
    expect_refused(doc, "image 0 (big.png) is 20000 x 100 pixels, more than 16384 on a side");
}

// A JPEG of w x h grey pixels, written by OpenImageIO (the tests' image library).
std::string jpeg_bytes(const std::string& path, int w, int h) {
    const std::vector<unsigned char> pixels(std::size_t(w) * std::size_t(h), 128);
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(w, h, 1, OIIO::TypeDesc::UINT8)) &&
                out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && out->close());
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(GltfHostile, JpegCutShortOrClaimingMorePixelsThanItsDataIsRefused) {
    // stb_image decodes both without complaint, padding what is missing.
    const std::string whole = jpeg_bytes(file("whole.jpg"), 64, 64);
    json doc = triangle();
    doc["images"] = {{{"uri", "whole.jpg"}}};
    EXPECT_NO_THROW(load_gltf(write(doc)));
    std::ofstream(file("half.jpg"), std::ios::binary) << whole.substr(0, whole.size() / 2);
    doc["images"][0]["uri"] = "half.jpg";
    expect_refused(doc, "image 0 (half.jpg) is a truncated JPEG (no end-of-image marker)");
    std::string claims = whole;   // the frame header (SOF0) says 16000 x 16000
    const std::size_t sof = claims.find("\xFF\xC0");
    ASSERT_NE(sof, std::string::npos);
    claims.replace(sof + 5, 4, std::string("\x3E\x80\x3E\x80", 4));
    std::ofstream(file("claims.jpg"), std::ios::binary) << claims;
    doc["images"][0]["uri"] = "claims.jpg";
    expect_refused(doc, "image 0 (claims.jpg) has too little data for its 16000 x 16000 pixels");
}

TEST_F(GltfHostile, PngCutShortIsRefusedNamingTheImage) {
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string("\0\0\0\x0dIHDR\0\0\0\x40\0\0\0\x40\x08\x00\x00\x00\x00", 21);   // 64 x 64 grey
    png += std::string(4, '\0');   // the chunk's CRC; no image data follows
    std::ofstream(file("cut.png"), std::ios::binary) << png;
    json doc = triangle();
    doc["images"] = {{{"uri", "cut.png"}}};
    expect_refused(doc, "image 0 (cut.png) cannot be decoded (a corrupt or truncated PNG)");
}

TEST_F(GltfHostile, ImageInAFormatGltfDoesNotAllowIsNotDecodedAndATextureOfItIsRefused) {
    // A BMP header claiming 20000 x 20000 pixels and no pixels: stb_image would allocate 1.2 GB and pad it.
    std::string bmp = "BM" + std::string(12, '\0');
    bmp += std::string("\x28\0\0\0\x20\x4e\0\0\x20\x4e\0\0\x01\0\x18\0", 16) + std::string(24, '\0');
    std::ofstream(file("huge.bmp"), std::ios::binary) << bmp;
    json doc = triangle();
    doc["images"] = {{{"uri", "huge.bmp"}}};
    std::string warnings;
    EXPECT_NO_THROW(load_gltf(write(doc), &warnings));
    EXPECT_NE(warnings.find("image 0 (huge.bmp) is not a PNG or JPEG image: not decoded"), std::string::npos)
        << warnings;
    doc["textures"] = {{{"source", 0}}};
    expect_refused(doc, "texture 0: image 0 is not a PNG or JPEG image");
}

TEST_F(GltfHostile, DataUriOfAMediaTypeGltfDoesNotAllowIsRefusedByItsTypeAndALongUriByItsEnds) {
    // tinygltf hands such a URI to the file callbacks as a path; the refusal names its media type, not its data.
    json doc = triangle();
    doc["images"] = {{{"uri", "data:image/x-tga;base64," + std::string(4000, 'A')}}};
    expect_refused(doc, "'data:image/x-tga;base64,...': a data URI of a media type glTF 2.0 does not allow");
    doc["images"][0]["uri"] = std::string(4000, 'x') + ".png";   // a file URI that long is shown by its two ends
    expect_refused(doc, "..." + std::string(56, 'x') + ".png': ");
}

TEST_F(GltfHostile, InputFilesListTheSceneAndEveryBufferRead) {
    const std::string path = write(triangle());
    const SceneAsset asset = load_gltf(path);
    ASSERT_EQ(asset.input_files.size(), 2u);
    EXPECT_EQ(asset.input_files[0], path);
    EXPECT_TRUE(fs::equivalent(asset.input_files[1], file("tri.bin")));
}

// ---------------------------------------------------------------------------------------------------------------
// The triangle budget.

TEST_F(GltfHostile, InstancingBeyondTheTriangleBudgetIsRefusedBeforeFlattening) {
    json doc = triangle();
    doc["nodes"] = json::array();
    const int instances = 5000;
    for (int i = 0; i < instances; ++i) doc["nodes"].push_back({{"mesh", 0}});
    doc["scenes"][0]["nodes"] = json::array();
    for (int i = 0; i < instances; ++i) doc["scenes"][0]["nodes"].push_back(i);
    const SceneAsset asset = load_gltf(write(doc));
    FlattenOptions options;
    options.max_triangles = instances - 1;
    try {
        flatten(asset, options);
        ADD_FAILURE() << "a scene over the budget was flattened";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("has 5000 triangles"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("--max-triangles"), std::string::npos) << e.what();
    }
    options.max_triangles = instances;
    EXPECT_EQ(flatten(asset, options).triangle_count(), std::size_t(instances));
    EXPECT_EQ(FlattenOptions{}.max_triangles, kDefaultMaxTriangles);
}

TEST_F(GltfHostile, AccessorsAddingUpPastTheLoaderBudgetAreRefusedBeforeCopying) {
    json doc = triangle();
    doc["accessors"][0]["count"] = (std::uint64_t(1) << 28) + 1;
    expect_refused(doc, "mesh 0 primitive 0: the file's accessors add up to more than 268435456 elements");
}

// ---------------------------------------------------------------------------------------------------------------
// Strict glTF: what tinygltf silently accepts.

TEST_F(GltfHostile, NodeMembersOfTheWrongJsonTypeAreRefused) {
    auto with = [&](const char* key, json value) {
        json doc = triangle();
        doc["nodes"][0][key] = value;
        return doc;
    };
    expect_refused(with("mesh", "0"), "node 0: mesh must be a non-negative integer");
    expect_refused(with("mesh", -1), "node 0: mesh must be a non-negative integer");
    expect_refused(with("camera", 0.5), "node 0: camera must be a non-negative integer");
    expect_refused(with("children", 1), "node 0: children must be an array");
    expect_refused(with("children", {"1"}), "node 0: children must be an array");
}

TEST_F(GltfHostile, TransformsOfTheWrongSizeAreRefused) {
    auto with = [&](const char* key, json value) {
        json doc = triangle();
        doc["nodes"][0][key] = value;
        return doc;
    };
    expect_refused(with("translation", {1, 2}), "translation must be an array of 3 numbers");
    expect_refused(with("rotation", {0, 0, 1}), "rotation must be an array of 4 numbers");
    expect_refused(with("scale", {1, 1, 1, 1}), "scale must be an array of 3 numbers");
    expect_refused(with("matrix", std::vector<double>(15, 0.0)), "matrix must be an array of 16 numbers");
    expect_refused(with("translation", {1, "2", 3}), "translation must be an array of 3 numbers");
}

// glTF 2.0, 5.25: a rotation is a unit quaternion. glm's mat4_cast of [1, 0, 0, 1] squashed the node's mesh to a
// sliver instead of turning it a quarter turn; a zero quaternion turned nothing, silently.
TEST_F(GltfHostile, RotationOfAnotherLengthIsNormalizedWithAWarningAndAZeroOneRefused) {
    json doc = triangle();
    doc["nodes"][0]["rotation"] = {1, 0, 0, 1};   // x, y, z, w: a quarter turn about x, length sqrt(2)
    std::string warnings;
    const SceneAsset asset = load_gltf(write(doc), &warnings);
    EXPECT_NE(warnings.find("node 0: rotation has length 1.414, not 1; normalized"), std::string::npos) << warnings;
    const Scene scene = flatten(asset, FlattenOptions{});
    ASSERT_EQ(scene.triangle_count(), 1u);
    // (0, 1, 0) turned a quarter about x is (0, 0, 1): the triangle keeps its size.
    EXPECT_NEAR(scene.positions[2].x, 0.0f, 1e-6f);
    EXPECT_NEAR(scene.positions[2].y, 0.0f, 1e-6f);
    EXPECT_NEAR(scene.positions[2].z, 1.0f, 1e-6f);

    doc["nodes"][0]["rotation"] = {0.7071, 0, 0, 0.7071};   // float rounding: no warning, as written
    warnings.clear();
    load_gltf(write(doc), &warnings);
    EXPECT_EQ(warnings.find("rotation"), std::string::npos) << warnings;

    doc["nodes"][0]["rotation"] = {0, 0, 0, 0};
    expect_refused(doc, "node 0: rotation has length 0, not a unit quaternion");
}

// An animation's keys as binary data (where NaN can be written): times and values of one channel of node 0.
json animated_triangle(const std::string& path, const std::string& interpolation, const std::vector<float>& times,
                       const std::vector<float>& values) {
    json doc = json::parse(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]})");
    std::vector<unsigned char> bytes;
    gltf_test::append(bytes, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    gltf_test::append(bytes, times);
    gltf_test::append(bytes, values);
    const std::size_t n = times.size() * 4, components = path == "rotation" ? 4 : 3;
    doc["buffers"] = {{{"uri", gltf_test::data_uri(bytes)}, {"byteLength", bytes.size()}}};
    doc["bufferViews"] = {{{"buffer", 0}, {"byteLength", 36}},
                          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", n}},
                          {{"buffer", 0}, {"byteOffset", 36 + n}, {"byteLength", values.size() * 4}}};
    doc["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                        {{"bufferView", 1}, {"componentType", 5126}, {"count", times.size()}, {"type", "SCALAR"}},
                        {{"bufferView", 2}, {"componentType", 5126}, {"count", values.size() / components},
                         {"type", components == 4 ? "VEC4" : "VEC3"}}};
    json animation = json::parse(R"({"samplers":[{"input":1,"output":2}],"channels":[{"sampler":0,
        "target":{"node":0}}]})");
    animation["samplers"][0]["interpolation"] = interpolation;
    animation["channels"][0]["target"]["path"] = path;
    doc["animations"] = json::array({animation});
    return doc;
}

// Keys glTF 2.0 (5.3.2, 5.3.3) does not allow are refused, naming the channel; none of these cases had a test.
TEST_F(GltfHostile, AnimationKeysThatAreNotFiniteIncreasingOrARotationAreRefused) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::string channel = "animation 0 channel 0: ";
    expect_refused(animated_triangle("translation", "LINEAR", {1, 0}, {0, 0, 0, 1, 0, 0}),
                   channel + "key times must be finite and increasing");
    expect_refused(animated_triangle("translation", "LINEAR", {0, nan}, {0, 0, 0, 1, 0, 0}),
                   channel + "key times must be finite and increasing");
    expect_refused(animated_triangle("translation", "LINEAR", {0, 1}, {0, 0, 0, nan, 0, 0}),
                   channel + "output values must be finite");
    expect_refused(animated_triangle("translation", "CUBICSPLINE", {0, 1}, {0, 0, 0, 1, 0, 0}),
                   channel + "input and output counts do not match");
    expect_refused(animated_triangle("rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, 0, 0}),
                   channel + "rotation key 1 has length 0, not a unit quaternion");
    // A cubic spline's tangents may be zero; its keys may not.
    const std::vector<float> zero(4, 0.0f), identity{0, 0, 0, 1};
    auto cubic = [&](const std::vector<float>& key1) {
        std::vector<float> v;
        for (const auto* part : {&zero, &identity, &zero, &zero, &key1, &zero})
            v.insert(v.end(), part->begin(), part->end());
        return animated_triangle("rotation", "CUBICSPLINE", {0, 1}, v);
    };
    EXPECT_NO_THROW(load_gltf(write(cubic(identity))));
    expect_refused(cubic(zero), channel + "rotation key 1 has length 0, not a unit quaternion");
}

TEST_F(GltfHostile, ProjectiveMatrixIsWarnedOf) {
    json doc = triangle();
    doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0};
    std::string warnings;
    load_gltf(write(doc), &warnings);
    EXPECT_NE(warnings.find("node 0: matrix's last row is not 0, 0, 0, 1"), std::string::npos) << warnings;
}

// The camera looks along its node's -Z axis; a scale of 0 leaves none (it looked down world -Z, silently).
TEST_F(GltfHostile, CameraScaledToNothingIsRefused) {
    json doc = triangle();
    doc["cameras"] = json::parse(R"([{"type":"perspective","perspective":{"yfov":1.0,"znear":0.01}}])");
    doc["nodes"].push_back(json::parse(R"({"camera":0,"translation":[0,0,3],"scale":[0,0,0]})"));
    doc["scenes"][0]["nodes"].push_back(1);
    const SceneAsset asset = load_gltf(write(doc));
    try {
        flatten(asset, FlattenOptions{});
        ADD_FAILURE() << "a camera scaled to nothing was accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("the camera's node transforms have no -Z axis"), std::string::npos)
            << e.what();
    }
    doc["nodes"][1]["scale"] = {1e-30, 1e-30, 1e-30};   // tiny is not nothing
    EXPECT_NO_THROW(flatten(load_gltf(write(doc)), FlattenOptions{}));
}

TEST_F(GltfHostile, SceneIndexOutOfRangeIsRefused) {
    json doc = triangle();
    doc["scene"] = 3;
    expect_refused(doc, "scene 3 does not exist");
    doc["scene"] = "0";
    expect_refused(doc, "scene must be a non-negative integer");
}

TEST_F(GltfHostile, AssetVersionOtherThanTwoIsRefused) {
    json doc = triangle();
    doc["asset"]["version"] = "1.0";
    expect_refused(doc, "asset.version is '1.0'");
    doc["asset"].erase("version");
    expect_refused(doc, "asset.version is missing");
}

TEST_F(GltfHostile, RequiredExtensionTheLoaderLacksIsRefused) {
    json doc = triangle();
    doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    expect_refused(doc, "requires extension KHR_draco_mesh_compression");
}

TEST_F(GltfHostile, RequiredExtensionTheLoaderSupportsLoads) {
    json doc = triangle();
    doc["extensionsUsed"] = {"KHR_materials_ior"};
    doc["extensionsRequired"] = {"KHR_materials_ior"};
    doc["materials"] = {{{"extensions", {{"KHR_materials_ior", {{"ior", 1.33}}}}}}};
    doc["meshes"][0]["primitives"][0]["material"] = 0;
    const SceneAsset asset = load_gltf(write(doc));
    ASSERT_EQ(asset.materials.size(), 1u);
    EXPECT_FLOAT_EQ(asset.materials[0].ior, 1.33f);
}

TEST_F(GltfHostile, EachUsedExtensionTheRendererLacksIsWarnedAboutOnceInNameOrder) {
    json doc = triangle();
    // Listed and used twice; used without being listed (on a material, a primitive and a node); listed and
    // not used; and two the loader reads, which must not be warned about.
    // Metadata extensions (KHR_xmp_json_ld) change no image and are not warned about either.
    doc["extensionsUsed"] = {"KHR_materials_sheen", "KHR_materials_clearcoat", "EXT_listed_only", "KHR_materials_ior",
                             "KHR_xmp_json_ld"};
    doc["asset"]["extensions"] = {{"KHR_xmp_json_ld", {{"packet", 0}}}};
    // An application's own data under "extras" is not glTF: an "extensions" key in it names no extension.
    doc["nodes"][0]["extras"] = {{"extensions", {{"EXT_inside_extras", json::object()}}}};
    doc["materials"] = {{{"extensions", {{"KHR_materials_clearcoat", json::object()},
                                         {"KHR_materials_ior", {{"ior", 1.4}}}}}},
                        {{"extensions", {{"KHR_materials_clearcoat", json::object()},
                                         {"KHR_materials_sheen", json::object()}}}}};
    doc["nodes"][0]["extensions"] = {{"EXT_mesh_gpu_instancing", json::object()},
                                     {"KHR_lights_punctual", {{"light", 0}}}};
    doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}}};
    doc["meshes"][0]["primitives"][0]["material"] = 0;
    doc["meshes"][0]["primitives"][0]["extensions"] = {{"EXT_on_a_primitive", json::object()}};
    std::string warnings;
    load_gltf(write(doc), &warnings);
    std::vector<std::string> named;
    std::istringstream lines(warnings);
    for (std::string line; std::getline(lines, line);) {
        const std::string prefix = "uses extension ";
        if (!line.starts_with(prefix)) continue;
        named.push_back(line.substr(prefix.size(), line.find(',') - prefix.size()));
        EXPECT_TRUE(line.ends_with(", which this renderer does not implement; rendered without it")) << line;
    }
    EXPECT_EQ(named, (std::vector<std::string>{"EXT_listed_only", "EXT_mesh_gpu_instancing", "EXT_on_a_primitive",
                                               "KHR_materials_clearcoat", "KHR_materials_sheen"}))
        << warnings;
}

// ---------------------------------------------------------------------------------------------------------------
// Values: refused when they do not fit a float, clamped (with a warning) when outside glTF's range.

TEST_F(GltfHostile, ValuesThatDoNotFitAFloatAreRefused) {
    json doc = triangle();
    doc["meshes"][0]["primitives"][0]["material"] = 0;
    doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1e39, 1, 1, 1}}}}}};
    expect_refused(doc, "material 0: baseColorFactor is 1e+39, which does not fit a float");
    doc["materials"] = {{{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 1e39}}}}}}};
    expect_refused(doc, "emissiveStrength is 1e+39");
    doc["materials"] = json::array();
    doc["meshes"][0]["primitives"][0].erase("material");
    doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", -1e39}}}}}}};
    expect_refused(doc, "light 0: intensity is -1e+39");
    doc.erase("extensions");
    doc["nodes"][0]["translation"] = {0, 1e300, 0};
    expect_refused(doc, "node 0: translation is 1e+300");
}

TEST_F(GltfHostile, NegativeAndOutOfRangeValuesAreClampedWithAWarning) {
    json doc = triangle();
    doc["meshes"][0]["primitives"][0]["material"] = 0;
    doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {-0.5, 2, 0.5, 1}}}},
                         {"emissiveFactor", {-1, 0, 0}},
                         {"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}}};
    doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", -5}}}}}}};
    doc["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    std::string warnings;
    const SceneAsset asset = load_gltf(write(doc), &warnings);
    EXPECT_EQ(asset.materials[0].base_color, glm::vec4(0.0f, 1.0f, 0.5f, 1.0f));
    EXPECT_EQ(asset.materials[0].emissive, glm::vec3(0.0f));
    EXPECT_EQ(asset.materials[0].ior, 1.0f);
    EXPECT_EQ(asset.lights[0].intensity, 0.0f);
    EXPECT_NE(warnings.find("baseColorFactor -0.5 is outside [0, 1]; clamped to 0"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("light 0: intensity -5"), std::string::npos) << warnings;
}

TEST_F(GltfHostile, SpotWhoseInnerConeIsNotInsideItsOuterConeIsWarnedOfAndHasAHardEdge) {
    json doc = triangle();
    doc["extensions"] = {{"KHR_lights_punctual",
                          {{"lights", {{{"type", "spot"}, {"spot", {{"innerConeAngle", 1.0}, {"outerConeAngle", 0.5}}}},
                                       {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}}}}}}};
    doc["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    doc["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    doc["scenes"][0]["nodes"].push_back(1);
    std::string warnings;
    const SceneAsset asset = load_gltf(write(doc), &warnings);
    ASSERT_EQ(asset.lights.size(), 2u);
    EXPECT_EQ(asset.lights[0].inner_cone, std::nextafter(0.5f, 0.0f)) << "just inside the outer cone";
    EXPECT_EQ(asset.lights[0].outer_cone, 0.5f);
    EXPECT_NE(warnings.find("light 0: innerConeAngle 1 is not below outerConeAngle 0.5"), std::string::npos)
        << warnings;
    EXPECT_EQ(asset.lights[1].inner_cone, 0.25f) << "a valid cone is kept as it is";
    EXPECT_EQ(warnings.find("light 1"), std::string::npos) << warnings;
}

TEST_F(GltfHostile, AlphaCutoffBelowZeroIsClampedBeyondAFloatRefusedAndAnUnknownAlphaModeIsOpaque) {
    json doc = triangle();
    doc["meshes"][0]["primitives"][0]["material"] = 0;
    doc["materials"] = {{{"alphaMode", "MASK"}, {"alphaCutoff", -0.25}}, {{"alphaMode", "SOMETIMES"}}};
    std::string warnings;
    const SceneAsset asset = load_gltf(write(doc), &warnings);
    EXPECT_EQ(asset.materials[0].alpha_mode, AlphaMode::Mask);
    EXPECT_EQ(asset.materials[0].alpha_cutoff, 0.0f);
    EXPECT_NE(warnings.find("material 0: alphaCutoff -0.25 is outside"), std::string::npos) << warnings;
    EXPECT_EQ(asset.materials[1].alpha_mode, AlphaMode::Opaque);
    EXPECT_NE(warnings.find("material 1: alphaMode 'SOMETIMES' is unknown"), std::string::npos) << warnings;
    doc["materials"][0]["alphaCutoff"] = 1e39;
    expect_refused(doc, "material 0: alphaCutoff is 1e+39, which does not fit a float");
}

}  // namespace

// Texture references inside material extensions are JSON numbers tinygltf does not check: a fraction, a huge or a
// negative index, or a texture that does not exist, is refused before anything reads it.
TEST_F(GltfHostile, ExtensionTextureIndexThatIsNotATextureIsRefused) {
    for (const auto& [index, expected] : std::vector<std::pair<json, std::string>>{
             {json(0.5), "transmissionTexture index is 0.5"},
             {json(1e300), "transmissionTexture index is"},
             {json(-7), "transmissionTexture index is -7"},
             {json(3), "transmissionTexture 3 does not exist"}}) {
        json doc = triangle();
        doc["materials"] = json::parse(R"([{"extensions":{"KHR_materials_transmission":{"transmissionFactor":1}}}])");
        doc["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionTexture"] = {{"index", index}};
        doc["meshes"][0]["primitives"][0]["material"] = 0;
        expect_refused(doc, expected);
    }
}

}  // namespace rt
