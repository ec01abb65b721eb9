// Tangents for normal maps (tangents.h) and their flattening (scene.cpp): generated on known quads, handedness,
// degenerate uvs, world transforms, and no tangents at all for scenes without a normal map.
#include <gtest/gtest.h>

#include <cmath>

#include "common/scene/builtin/builtin_scenes.h"
#include "tangents.h"

namespace rt {
namespace {

// A unit quad in the XY plane facing +Z, counter-clockwise; uv (0, 0) at the top left (glTF: v down the image).
Primitive quad(bool mirror_u) {
    Primitive p;
    p.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    p.normals.assign(4, glm::vec3(0, 0, 1));
    const float u0 = mirror_u ? 1.0f : 0.0f, u1 = 1.0f - u0;
    p.uvs = {{u0, 1}, {u1, 1}, {u1, 0}, {u0, 0}};
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

void expect_near(const glm::vec4& a, const glm::vec4& b) {
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(a[i], b[i], 1e-6f) << i;
}

TEST(Tangents, KnownQuadGetsUAlongXAndRightHandedness) {
    for (const glm::vec4& t : generate_tangents(quad(false))) expect_near(t, {1, 0, 0, 1});
}

TEST(Tangents, MirroredUvsGetNegativeHandedness) {
    // u grows along -X; v still goes down the image, so -dP/dv is +Y while cross(n, t) = cross(Z, -X) = -Y.
    for (const glm::vec4& t : generate_tangents(quad(true))) expect_near(t, {-1, 0, 0, -1});
}

TEST(Tangents, DegenerateUvsGiveAUnitTangentOrthogonalToTheNormal) {
    Primitive p = quad(false);
    p.uvs.assign(4, glm::vec2(0.5f));   // every triangle has zero uv area
    for (const glm::vec4& t : generate_tangents(p)) {
        EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(glm::vec3(t), glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
        EXPECT_EQ(t.w, 1.0f);
    }
    p.uvs.clear();   // no uvs at all
    for (const glm::vec4& t : generate_tangents(p)) EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-6f);
}

TEST(Tangents, GivenTangentsAreKept) {
    Primitive p = quad(false);
    p.tangents.assign(4, glm::vec4(0, 1, 0, -1));
    EXPECT_EQ(primitive_tangents(p), p.tangents);
}

SceneAsset one_quad_scene(bool normal_map, const glm::vec3& scale) {
    SceneAsset a;
    Texture t;
    t.width = t.height = 1;
    t.rgba8 = {128, 128, 255, 255};
    a.textures.push_back(t);
    Material m;
    m.normal_texture = normal_map ? 0 : -1;
    a.materials.push_back(m);
    Primitive p = quad(false);
    p.material = 0;
    Mesh mesh;
    mesh.primitives.push_back(p);
    a.meshes.push_back(mesh);
    Node n;
    n.mesh = 0;
    n.scale = scale;
    a.nodes.push_back(n);
    a.roots = {0};
    return a;
}

TEST(Tangents, FlattenedOnlyWhenAUsedMaterialHasANormalMap) {
    EXPECT_TRUE(flatten(one_quad_scene(false, glm::vec3(1)), {}).tangents.empty());
    EXPECT_TRUE(flatten(make_builtin_scene("whitted"), {}).tangents.empty());
    const Scene s = flatten(one_quad_scene(true, glm::vec3(1)), {});
    ASSERT_EQ(s.tangents.size(), s.positions.size());
    for (const glm::vec4& t : s.tangents) expect_near(t, {1, 0, 0, 1});
}

TEST(Tangents, AMirroringNodeFlipsHandedness) {
    // Scale -1 in X mirrors the quad: the tangent (dP/du) turns to -X and w flips, so the bitangent
    // w cross(n, t) still points along -dP/dv (+Y) in world space.
    const Scene s = flatten(one_quad_scene(true, {-1, 1, 1}), {});
    ASSERT_EQ(s.tangents.size(), 6u);
    for (std::size_t i = 0; i < 6; ++i) {
        expect_near(s.tangents[i], {-1, 0, 0, -1});
        const glm::vec3 b = s.tangents[i].w * glm::cross(s.normals[i], glm::vec3(s.tangents[i]));
        EXPECT_NEAR(b.y, 1.0f, 1e-6f);
    }
}

}  // namespace
}  // namespace rt
