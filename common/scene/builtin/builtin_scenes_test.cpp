// The built-in scenes and the mesh generators.
#include "builtin_scenes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "common/scene/gltf/gltf_io.h"

namespace rt {
namespace {

using Corner = std::array<float, 3>;

Corner key(const glm::vec3& p) { return {p.x, p.y, p.z}; }

// Counts, for every undirected edge (by exact vertex position), how many triangles use it.
std::map<std::pair<Corner, Corner>, int> edge_uses(const Primitive& p) {
    std::map<std::pair<Corner, Corner>, int> uses;
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            Corner a = key(p.positions[p.indices[t + std::size_t(k)]]);
            Corner b = key(p.positions[p.indices[t + std::size_t((k + 1) % 3)]]);
            if (b < a) std::swap(a, b);
            ++uses[{a, b}];
        }
    return uses;
}

// Every triangle is non-degenerate and its winding normal points away from `center`.
void expect_outward_triangles(const Primitive& p, const glm::vec3& center) {
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]],
                        c = p.positions[p.indices[t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        ASSERT_GT(glm::length(n), 0.0f) << "degenerate triangle " << t / 3;
        EXPECT_GT(glm::dot(n, (a + b + c) / 3.0f - center), 0.0f) << "triangle " << t / 3 << " faces inward";
    }
}

// Projects a world point with the scene's camera; true when it lands inside an image of the given aspect.
bool in_view(const Camera& c, const glm::vec3& p, float aspect) {
    const glm::vec3 d = p - c.position;
    const float z = glm::dot(d, c.forward);
    if (z <= 0) return false;
    const float h = std::tan(0.5f * c.yfov);
    return std::abs(glm::dot(d, c.up) / z) < h && std::abs(glm::dot(d, c.right) / z) < h * aspect;
}

// Lambert shading of a white surface at p with normal n by every light: kd / pi * I / d^2 * cos.
float white_lambert(const Scene& s, const glm::vec3& p, const glm::vec3& n) {
    float sum = 0;
    for (const Light& l : s.lights) {
        const glm::vec3 to = l.position - p;
        const float d2 = glm::dot(to, to);
        sum += l.intensity / 3.14159265f / d2 * std::max(0.0f, glm::dot(n, to / std::sqrt(d2)));
    }
    return sum;
}

// ---------------------------------------------------------------------------------------------------------------

TEST(UvSphere, IsClosedEveryEdgeSharedByTwoTriangles) {
    for (auto [segments, rings] : {std::pair{48, 24}, std::pair{16, 8}, std::pair{3, 2}, std::pair{7, 5}}) {
        const Primitive p = make_uv_sphere({1.5f, -2.0f, 0.25f}, 0.7f, segments, rings, 3);
        EXPECT_EQ(p.material, 3);
        EXPECT_EQ(p.indices.size(), std::size_t(3 * 2 * segments * (rings - 1)));
        for (const auto& [edge, uses] : edge_uses(p)) EXPECT_EQ(uses, 2);
        expect_outward_triangles(p, {1.5f, -2.0f, 0.25f});
        ASSERT_EQ(p.normals.size(), p.positions.size());
        ASSERT_EQ(p.uvs.size(), p.positions.size());
        for (std::size_t i = 0; i < p.positions.size(); ++i) {
            EXPECT_NEAR(glm::length(p.positions[i] - glm::vec3(1.5f, -2.0f, 0.25f)), 0.7f, 1e-5f);
            EXPECT_NEAR(glm::length(p.normals[i]), 1.0f, 1e-5f);
            for (std::uint32_t idx : p.indices) ASSERT_LT(idx, p.positions.size());
        }
    }
}

TEST(Box, HasTwelveOutwardTrianglesWithFlatNormals) {
    const Primitive p = make_box({-1, 0, 2}, {3, 1, 2.5f}, 0);
    EXPECT_EQ(p.positions.size(), 24u);
    EXPECT_EQ(p.indices.size(), 36u);
    expect_outward_triangles(p, {1, 0.5f, 2.25f});
    for (const auto& [edge, uses] : edge_uses(p)) EXPECT_EQ(uses, 2);
    // Each vertex normal equals its face's winding normal.
    for (std::size_t t = 0; t < p.indices.size(); t += 3) {
        const glm::vec3 a = p.positions[p.indices[t]], b = p.positions[p.indices[t + 1]],
                        c = p.positions[p.indices[t + 2]];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) EXPECT_EQ(p.normals[p.indices[t + std::size_t(k)]], n);
    }
}

TEST(BuiltinScenes, EveryOneHasACameraALightAndTriangles) {
    for (const std::string& name : builtin_scene_names()) {
        SCOPED_TRACE(name);
        const SceneAsset a = make_builtin_scene(name);
        EXPECT_FALSE(a.cameras.empty());
        const Scene s = flatten(a, {});
        EXPECT_GT(s.light_count(), 0u);   // a punctual light, or an area light (soft_shadows, office_soft)
        EXPECT_FALSE(s.default_camera);
        EXPECT_FALSE(s.default_light);
        EXPECT_GT(s.triangle_count(), 0u);
        EXPECT_GT(s.background.b, 0.0f);
        for (const Material& m : s.materials) EXPECT_NE(m.name, "default");   // every primitive has a material
        // The camera looks at the scene's centre region, and the light lights it without blowing it out.
        EXPECT_TRUE(in_view(s.camera, s.bounds.center(), 4.0f / 3.0f));
    }
}

TEST(BuiltinScenes, WhittedShowsBothSpheresOnATexturedFloorWithReasonableExposure) {
    const SceneAsset a = make_builtin_scene("whitted");
    const Scene s = flatten(a, {});
    ASSERT_EQ(a.textures.size(), 1u);
    EXPECT_TRUE(a.textures[0].nearest);
    EXPECT_EQ(a.textures[0].width * a.textures[0].height * 4, int(a.textures[0].rgba8.size()));
    EXPECT_TRUE(in_view(s.camera, {0.5f, 1.1f, 0.3f}, 4.0f / 3.0f));     // glass sphere
    EXPECT_TRUE(in_view(s.camera, {-1.0f, 1.0f, -1.8f}, 4.0f / 3.0f));   // mirror sphere
    // White floor just below the spheres shades to between 0.3 and 1.
    for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(-1, 0, -1), glm::vec3(2, 0, 1)}) {
        const float v = white_lambert(s, p, {0, 1, 0});
        EXPECT_GT(v, 0.3f);
        EXPECT_LT(v, 1.0f);
    }
}

TEST(BuiltinScenes, CornellWallsFaceInwardAndFloorIsWellExposed) {
    const SceneAsset a = make_builtin_scene("cornell");
    const Scene s = flatten(a, {});
    const glm::vec3 inside(0, 1, 0);
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        const glm::vec3 p = s.positions[3 * t];
        // The walls (triangles touching the box's bounding planes) face the inside.
        if (std::abs(std::abs(p.x) - 1) < 1e-6f || std::abs(p.y - 2) < 1e-6f || std::abs(p.z + 1) < 1e-6f) {
            EXPECT_GT(glm::dot(s.normals[3 * t], inside - p), 0.0f) << "triangle " << t;
        }
    }
    const float floor = white_lambert(s, {0, 0, 0}, {0, 1, 0}) * 0.75f;
    EXPECT_GT(floor, 0.4f);
    EXPECT_LT(floor, 1.0f);
}

// Inside the box lo..hi, away from its faces.
bool strictly_inside(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    return glm::all(glm::greaterThan(p, lo)) && glm::all(glm::lessThan(p, hi));
}

TEST(BuiltinScenes, MirrorBoxIsAnObjectOfSeveralHundredTrianglesInsideSixMirrorsFacingIn) {
    const SceneAsset a = make_builtin_scene("mirror_box");
    const Scene s = flatten(a, {});
    const glm::vec3 lo = s.bounds.lo, hi = s.bounds.hi, inside = 0.5f * (lo + hi);
    std::size_t wall_triangles = 0;
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        const glm::vec3 p = s.positions[3 * t], q = s.positions[3 * t + 1], r = s.positions[3 * t + 2];
        bool on_wall = false;   // all three corners on one face of the box
        for (int k = 0; k < 3; ++k)
            for (float face : {lo[k], hi[k]}) on_wall |= p[k] == face && q[k] == face && r[k] == face;
        if (!on_wall) continue;
        ++wall_triangles;
        EXPECT_EQ(s.materials[s.material_ids[t]].metallic, 1.0f) << "wall triangle " << t << " is not a mirror";
        EXPECT_GT(glm::dot(s.normals[3 * t], inside - p), 0.0f) << "wall triangle " << t << " faces out";
    }
    EXPECT_EQ(wall_triangles, 12u);   // six quads
    const std::size_t object = s.triangle_count() - wall_triangles;
    EXPECT_GE(object, 300u);
    EXPECT_LE(object, 1000u);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(strictly_inside(s.lights[0].position, lo, hi));
    EXPECT_TRUE(strictly_inside(s.camera.position, lo, hi));
}

TEST(BuiltinScenes, OfficeIsAFurnishedRoomOfTensOfThousandsOfTrianglesInManyMeshesAndOneLight) {
    const SceneAsset a = make_builtin_scene("office");
    const Scene s = flatten(a, {});
    EXPECT_EQ(s.triangle_count(), 25424u);   // under 60,000: brute force (stage 02) stays within llvmpipe's loop limit
    EXPECT_EQ(a.meshes.size(), 330u);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(strictly_inside(s.lights[0].position, s.bounds.lo, s.bounds.hi));
    EXPECT_TRUE(strictly_inside(s.camera.position, s.bounds.lo, s.bounds.hi));
    for (const Material& m : s.materials) {   // diffuse only: every secondary ray is a shadow ray
        EXPECT_EQ(m.metallic, 0.0f) << m.name;
        EXPECT_EQ(m.transmission, 0.0f) << m.name;
    }
    // The desks under the light are lit to between 0.2 and 1 (white Lambert).
    const float desk = white_lambert(s, {0.0f, 0.76f, -1.6f}, {0, 1, 0});
    EXPECT_GT(desk, 0.2f);
    EXPECT_LT(desk, 1.0f);
}

TEST(BuiltinScenes, DiffuseHasOnlyDiffuseUntexturedMaterials) {
    const Scene s = flatten(make_builtin_scene("diffuse"), {});
    for (const Material& m : s.materials) {
        EXPECT_EQ(m.metallic, 0.0f);
        EXPECT_EQ(m.roughness, 1.0f);
        EXPECT_EQ(m.transmission, 0.0f);
        EXPECT_EQ(m.base_color_texture, -1);
    }
    EXPECT_EQ(s.lights.size(), 1u);
}

TEST(BuiltinScenes, DynamicMovesForTwoSecondsThenHolds) {
    const SceneAsset a = make_builtin_scene("dynamic");
    ASSERT_FALSE(a.animations.empty());
    EXPECT_NEAR(a.animations[0].duration(), 2.0f, 1e-6f);
    auto at = [&](float t) {
        FlattenOptions o;
        o.time = t;
        return flatten(a, o).positions;
    };
    EXPECT_NE(at(0.0f), at(0.25f));
    EXPECT_NE(at(0.25f), at(0.75f));
    EXPECT_EQ(at(2.0f), at(3.0f));
    // The bouncing sphere stays above the floor.
    for (float t = 0; t <= 2.0f; t += 0.05f)
        for (const glm::vec3& p : at(t)) EXPECT_GE(p.y, -1e-4f);
}

TEST(BuiltinScenes, SpheresCountMatchesTheRequestAndAllAreInView) {
    const std::size_t per_sphere = make_uv_sphere({0, 0, 0}, 1, 16, 8, 0).indices.size() / 3;
    for (int n : {1, 2, 10, 100, 10000}) {
        SCOPED_TRACE(n);
        SceneAsset a = make_builtin_scene("spheres:" + std::to_string(n));
        std::size_t sphere_nodes = 0;
        for (const Node& node : a.nodes) sphere_nodes += node.name.rfind("sphere ", 0) == 0;
        EXPECT_EQ(sphere_nodes, std::size_t(n));
        if (n <= 100) {
            const Scene s = flatten(a, {});
            EXPECT_EQ(s.triangle_count(), 2 + std::size_t(n) * per_sphere);   // floor quad + spheres
        }
        // Every sphere is in view (the camera only needs the nodes: drop the geometry to keep this fast).
        for (Mesh& m : a.meshes) m.primitives.clear();
        const Scene s = flatten(a, {});
        for (const Node& node : a.nodes) {
            if (node.mesh < 0 || node.name == "floor") continue;
            for (float dx : {-0.35f, 0.35f})
                EXPECT_TRUE(in_view(s.camera, node.translation + glm::vec3(dx, 0.35f, dx), 4.0f / 3.0f)) << node.name;
        }
    }
}

TEST(BuiltinScenes, BadSphereCountThrowsSceneError) {
    for (const char* name : {"spheres:0", "spheres:10001", "spheres:-1", "spheres:+5", "spheres:abc", "spheres:",
                             "spheres:12x", "spheres:1e3", "spheres: 5", "spheres:99999999999999999999"}) {
        try {
            make_builtin_scene(name);
            ADD_FAILURE() << name;
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find("bad sphere count"), std::string::npos) << e.what();
        }
    }
    EXPECT_NO_THROW(make_builtin_scene("spheres:10000"));
    EXPECT_NO_THROW(make_builtin_scene("spheres:1"));
}

TEST(BuiltinScenes, UnknownNameThrowsSceneErrorListingTheKnownOnes) {
    try {
        make_builtin_scene("teapot");
        FAIL();
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("unknown built-in scene 'teapot'"), std::string::npos) << what;
        for (const std::string& name : builtin_scene_names()) EXPECT_NE(what.find(name), std::string::npos) << what;
    }
}

TEST(BuiltinScenes, FarIsWhittedTranslatedByTenThousand) {
    const Scene w = flatten(make_builtin_scene("whitted"), {});
    const Scene f = flatten(make_builtin_scene("far"), {});
    ASSERT_EQ(w.triangle_count(), f.triangle_count());
    const glm::vec3 offset(1e4f);
    for (std::size_t i = 0; i < w.positions.size(); ++i) {
        const glm::vec3 d = f.positions[i] - w.positions[i] - offset;
        EXPECT_LT(glm::length(d), 2e-3f);   // float spacing at 1e4 is ~1e-3
        EXPECT_EQ(w.normals[i], f.normals[i]);
    }
    EXPECT_LT(glm::length(f.camera.position - w.camera.position - offset), 2e-3f);
    EXPECT_EQ(f.camera.forward, w.camera.forward);
    ASSERT_EQ(f.lights.size(), w.lights.size());
    EXPECT_LT(glm::length(f.lights[0].position - w.lights[0].position - offset), 2e-3f);
    EXPECT_EQ(f.lights[0].intensity, w.lights[0].intensity);
}

}  // namespace
}  // namespace rt
