// How the glTF loader reads a primitive's vertex data (glTF 2.0, 3.6 and 3.7): triangle strips and fans, sparse
// accessors and accessors without a buffer view, KHR_mesh_quantization's integer attributes, morph targets at the
// mesh's default weights, vertex colours (COLOR_0), interleaved strides and byte indices. Each case writes a small
// file whose buffer is a base64 data URI (gltf_test_support.h).
#include "gltf_io.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "gltf_test_support.h"

namespace rt {
namespace {

using namespace gltf_test;

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
    // A target's POSITION with fewer entries than the primitive's: the message names both, with both counts.
    std::string short_target = gltf("1");
    const auto replace = [&](const std::string& from, const std::string& to) {
        const std::size_t at = short_target.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        short_target.replace(at, from.size(), to);
    };
    replace(R"("targets":[{"POSITION":2,)", R"("targets":[{"POSITION":4,)");
    replace(R"("type":"VEC3"}],"bufferViews")",
            R"("type":"VEC3"},{"bufferView":0,"byteOffset":72,"componentType":5126,"count":2,"type":"VEC3"}],)"
            R"("bufferViews")");
    write_text(dir.file("short.gltf"), short_target);
    expect_one_line_scene_error(dir.file("short.gltf"),
                                "mesh 0 primitive 0 target 0: POSITION has 2 entries but the primitive's POSITION has 3");
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

}  // namespace
}  // namespace rt
