// The scene model: node transforms, animation sampling, flattening, default camera and light.
// Over 450 lines by choice: every case builds its asset from the same few helpers below (triangle, single,
// animated, room_with_camera, expect_near), and the defaults' cases (scene_defaults.cpp) go through flatten() too.
#include "scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace rt {
namespace {

constexpr float kEps = 1e-5f;

void expect_near(const glm::vec3& a, const glm::vec3& b, float eps = kEps) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

glm::vec4 xyzw(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }

// One triangle in the XY plane, counter-clockwise seen from +Z, as the only mesh.
Primitive triangle(int material = -1) {
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.indices = {0, 1, 2};
    p.material = material;
    return p;
}

// An asset with one mesh (the given primitive) on node 0, a root.
SceneAsset single(const Primitive& p) {
    SceneAsset a;
    Mesh m;
    m.primitives.push_back(p);
    a.meshes.push_back(m);
    Node n;
    n.mesh = 0;
    a.nodes.push_back(n);
    a.roots = {0};
    return a;
}

// An asset whose node 0 is moved by one channel.
SceneAsset animated(AnimationChannel c) {
    SceneAsset a = single(triangle());
    c.node = 0;
    Animation anim;
    anim.channels.push_back(c);
    a.animations.push_back(anim);
    return a;
}

Node evaluated_node(const SceneAsset& a, float t) {
    // Read back the node's placement through the flattened vertex 0 (the local origin).
    FlattenOptions o;
    o.time = t;
    const Scene s = flatten(a, o);
    Node n;
    n.translation = s.positions.at(0);
    return n;
}

// ---------------------------------------------------------------------------------------------------------------

TEST(NodeTransform, LocalIsTranslateRotateScale) {
    Node n;
    n.translation = {1, 2, 3};
    n.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
    n.scale = {2, 2, 2};
    // S then R then T: (1,0,0) -> (2,0,0) -> (0,2,0) -> (1,4,3).
    expect_near(glm::vec3(n.local_transform() * glm::vec4(1, 0, 0, 1)), {1, 4, 3});
}

TEST(NodeTransform, MatrixReplacesTrs) {
    Node n;
    n.translation = {5, 5, 5};
    n.matrix = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -2));
    expect_near(glm::vec3(n.local_transform() * glm::vec4(0, 0, 0, 1)), {0, 0, -2});
}

TEST(Flatten, HierarchyComposesParentThenChild) {
    SceneAsset a = single(triangle());
    // Node 1 (root): rotate 90 degrees about Y then move by (10, 0, 0); node 0 (child): move by (1, 0, 0).
    a.nodes[0].translation = {1, 0, 0};
    Node parent;
    parent.translation = {10, 0, 0};
    parent.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));
    parent.children = {0};
    a.nodes.push_back(parent);
    a.roots = {1};
    const Scene s = flatten(a, {});
    ASSERT_EQ(s.triangle_count(), 1u);
    // Local origin: child -> (1,0,0); parent rotation about Y -> (0,0,-1); parent translation -> (10,0,-1).
    expect_near(s.positions[0], {10, 0, -1});
    expect_near(s.positions[1], {10, 0, -2});
    // The face normal +Z rotates to +X.
    expect_near(s.normals[0], {1, 0, 0});
}

TEST(Flatten, NormalsUseTheInverseTranspose) {
    Primitive p = triangle();
    const glm::vec3 n = glm::normalize(glm::vec3(1, 1, 0));
    p.positions = {{0, 0, 0}, {1, -1, 0}, {0, 0, 1}};   // plane x + y = 0, normal (1, 1, 0)/sqrt2
    p.normals = {n, n, n};
    SceneAsset a = single(p);
    a.nodes[0].scale = {2, 1, 1};
    const Scene s = flatten(a, {});
    // Scaling x by 2 turns the plane x + y = 0 into x/2 + y = 0; the inverse transpose diag(1/2, 1, 1) maps the
    // normal (1, 1, 0) to (0.5, 1, 0), perpendicular to it (a plain transform would give (2, 1, 0), which is not).
    const glm::vec3 expected = glm::normalize(glm::vec3(0.5f, 1, 0));
    for (int k = 0; k < 3; ++k) expect_near(s.normals[std::size_t(k)], expected);
    // It is perpendicular to the transformed edges.
    EXPECT_NEAR(glm::dot(s.positions[1] - s.positions[0], expected), 0.0f, kEps);
}

TEST(Flatten, MissingNormalsAreFlatPerFace) {
    Primitive p;
    p.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};   // non-indexed, two faces
    const Scene s = flatten(single(p), {});
    ASSERT_EQ(s.triangle_count(), 2u);
    for (int k = 0; k < 3; ++k) expect_near(s.normals[std::size_t(k)], {0, 1, 0});
    for (int k = 3; k < 6; ++k) expect_near(s.normals[std::size_t(k)], {0, 0, 1});
    for (const glm::vec2& uv : s.uvs) EXPECT_EQ(uv, glm::vec2(0.0f));
}

TEST(Flatten, MirroringTransformKeepsFrontFaceNormal) {
    SceneAsset a = single(triangle());
    a.nodes[0].scale = {1, 1, -1};   // mirror in Z: the front face now faces -Z (glTF 2.0, 3.7.2.1)
    const Scene s = flatten(a, {});
    expect_near(s.normals[0], {0, 0, -1});
}

TEST(Flatten, NonIndexedPrimitiveUsesConsecutiveTriples) {
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}, {9, 9, 9}};   // 7th ignored
    const Scene s = flatten(single(p), {});
    ASSERT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(s.positions[3], glm::vec3(5, 0, 0));
    EXPECT_EQ(s.material_ids.size() * 3, s.positions.size());
    EXPECT_EQ(s.normals.size(), s.positions.size());
    EXPECT_EQ(s.uvs.size(), s.positions.size());
}

TEST(Flatten, NonFiniteTrianglesAreDroppedAndCounted) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {nan, 0, 0}, {inf, 0, 0}};
    p.indices = {0, 1, 2, 0, 1, 3, 4, 1, 2, 2, 1, 0, 0, 1, 99};   // the last one is out of range
    std::size_t dropped = 0;
    const Scene s = flatten(single(p), {}, &dropped);
    EXPECT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(dropped, 3u);
    for (const glm::vec3& v : s.positions) EXPECT_TRUE(std::isfinite(v.x + v.y + v.z));
    EXPECT_TRUE(std::isfinite(s.bounds.diagonal()));
}

TEST(Flatten, DefaultMaterialAppendedForMaterialMinusOne) {
    SceneAsset a = single(triangle(-1));
    Material red;
    red.name = "red";
    a.materials.push_back(red);
    Mesh m2;
    m2.primitives.push_back(triangle(0));
    a.meshes.push_back(m2);
    Node n;
    n.mesh = 1;
    a.nodes.push_back(n);
    a.roots.push_back(1);
    const Scene s = flatten(a, {});
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.material_ids, (std::vector<std::uint32_t>{1, 0}));
    EXPECT_EQ(s.materials[1].metallic, 1.0f);   // glTF default material
    EXPECT_EQ(s.materials[1].roughness, 1.0f);
    // Without any -1 primitive nothing is appended.
    a.roots = {1};
    EXPECT_EQ(flatten(a, {}).materials.size(), 1u);
}

TEST(Flatten, EmptyAssetGetsDefaultsWithoutCrashing) {
    const Scene s = flatten(SceneAsset{}, {});
    EXPECT_EQ(s.triangle_count(), 0u);
    EXPECT_FALSE(s.materials.empty());
    EXPECT_TRUE(s.default_camera);
    EXPECT_TRUE(s.default_light);
    EXPECT_TRUE(std::isfinite(s.lights[0].intensity) && s.lights[0].intensity > 0);
    EXPECT_TRUE(std::isfinite(s.camera.position.x + s.camera.position.y + s.camera.position.z));
}

TEST(Flatten, DefaultCameraFramesTheBoundsAndDefaultLightLightsTheCenter) {
    Primitive p = triangle();
    p.positions = {{-3, -1, -2}, {5, 2, 1}, {0, 4, -6}};
    for (float aspect : {0.5f, 4.0f / 3.0f, 3.0f}) {
        FlattenOptions o;
        o.aspect = aspect;
        const Scene s = flatten(single(p), o);
        ASSERT_TRUE(s.default_camera);
        ASSERT_TRUE(s.default_light);
        const Camera& c = s.camera;
        EXPECT_NEAR(glm::length(c.forward), 1.0f, kEps);
        EXPECT_NEAR(glm::dot(c.forward, c.up), 0.0f, kEps);
        EXPECT_NEAR(glm::dot(c.forward, c.right), 0.0f, kEps);
        expect_near(glm::cross(c.forward, c.up), c.right);
        // Every vertex projects inside the image.
        const float h = std::tan(0.5f * c.yfov), w = h * aspect;
        for (const glm::vec3& v : s.positions) {
            const glm::vec3 d = v - c.position;
            const float z = glm::dot(d, c.forward);
            ASSERT_GT(z, c.znear);
            EXPECT_LE(std::abs(glm::dot(d, c.right) / z), w);
            EXPECT_LE(std::abs(glm::dot(d, c.up) / z), h);
        }
        // Light: irradiance pi at the center, so a white Lambertian surface facing it shades to 1.
        const Light& l = s.lights[0];
        EXPECT_EQ(l.type, LightType::Point);
        const float d = glm::length(l.position - s.bounds.center());
        EXPECT_NEAR(l.intensity / (d * d), 3.14159265f, 1e-4f);
        EXPECT_GT(l.position.y, s.bounds.hi.y);   // above the scene
    }
}

// A box room 4 x 3 x 4 (two triangles on the floor, one on the ceiling span the bounds) with a camera at `eye`
// looking down -Z: the defaults of docs/shading.md for a camera inside and outside the bounds.
SceneAsset room_with_camera(const glm::vec3& eye) {
    Primitive floor = triangle();
    floor.positions = {{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 3, 2}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    SceneAsset a = single(floor);
    a.cameras.push_back(Camera{});
    Node n;
    n.camera = 0;
    n.translation = eye;
    a.nodes.push_back(n);
    a.roots.push_back(1);
    return a;
}

TEST(Flatten, CameraInsideTheBoundsGetsTheHeadlightNormalisedWhereTheViewAxisLeavesThem) {
    const Scene s = flatten(room_with_camera({0.5f, 1.5f, 1.0f}), {});
    ASSERT_TRUE(s.default_light);
    EXPECT_TRUE(s.default_headlight);
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.type, LightType::Point);
    EXPECT_EQ(l.position, s.camera.position);   // at the eye: everything seen directly is lit
    // The view axis (-Z) leaves the bounds at z = -2, 3 units away: irradiance pi there.
    EXPECT_NEAR(l.intensity, 3.14159265f * 9.0f, 1e-4f);
    EXPECT_EQ(l.name, "default headlight");
}

TEST(Flatten, AFileCameraOutsideTheBoundsGetsTheHeadlightNormalisedAtTheirCentre) {
    // From outside, on a face, on an edge: wherever the file's camera stands, the light is at it.
    for (const glm::vec3 eye : {glm::vec3(0, 1.5f, 6), glm::vec3(0, 1.5f, 2), glm::vec3(0, 3, 0)}) {
        const Scene s = flatten(room_with_camera(eye), {});
        ASSERT_TRUE(s.default_light);
        EXPECT_TRUE(s.default_headlight) << eye.x << "," << eye.y << "," << eye.z;
        EXPECT_EQ(s.lights[0].position, s.camera.position);
        const float d = glm::length(s.bounds.center() - s.camera.position);
        EXPECT_NEAR(s.lights[0].intensity, 3.14159265f * d * d, 1e-4f * d * d);
    }
}

TEST(Flatten, TheAutoFramedCameraGetsTheKeyLight) {
    const Scene s = flatten(single(triangle()), {});
    ASSERT_TRUE(s.default_camera);
    EXPECT_FALSE(s.default_headlight);
    EXPECT_EQ(s.lights[0].name, "default light");
}

TEST(DefaultHeadlight, FlatOrEmptyBoundsAndAnAxisAlongAFaceGiveAFiniteLight) {
    Camera c;
    c.position = glm::vec3(0.0f);
    c.forward = glm::vec3(0, 0, -1);
    for (const Bounds& b : {Bounds{}, [] { Bounds f; f.add({-1, 0, -1}); f.add({1, 0, 1}); return f; }()}) {
        const Light l = default_headlight(b, c);
        EXPECT_TRUE(std::isfinite(l.intensity) && l.intensity > 0.0f);
    }
}

TEST(StrictlyInside, FacesAndEmptyBoundsAreNotInside) {
    Bounds b;
    b.add({0, 0, 0});
    b.add({1, 1, 1});
    EXPECT_TRUE(strictly_inside(b, {0.5f, 0.5f, 0.5f}));
    EXPECT_FALSE(strictly_inside(b, {0.0f, 0.5f, 0.5f}));
    EXPECT_FALSE(strictly_inside(b, {0.5f, 1.5f, 0.5f}));
    EXPECT_FALSE(strictly_inside(Bounds{}, {0.0f, 0.0f, 0.0f}));
}

TEST(Flatten, NoDefaultLightWhenDisabledOrPresent) {
    FlattenOptions o;
    o.add_default_light = false;
    EXPECT_TRUE(flatten(single(triangle()), o).lights.empty());
    SceneAsset a = single(triangle());
    a.lights.push_back(Light{});
    Node n;
    n.light = 0;
    a.nodes.push_back(n);
    a.roots.push_back(1);
    const Scene s = flatten(a, {});
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_FALSE(s.default_light);
}

TEST(Flatten, LightTakesPositionAndDirectionFromItsNode) {
    SceneAsset a = single(triangle());
    Light spot;
    spot.type = LightType::Spot;
    a.lights.push_back(spot);
    Node n;
    n.light = 0;
    n.translation = {1, 5, 2};
    n.rotation = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));   // -Z turns to -Y: pointing down
    a.nodes.push_back(n);
    a.roots.push_back(1);
    const Scene s = flatten(a, {});
    ASSERT_EQ(s.lights.size(), 1u);
    expect_near(s.lights[0].position, {1, 5, 2});
    expect_near(s.lights[0].direction, {0, -1, 0});
}

TEST(Flatten, CameraFrameFromScaledNodeIsOrthonormal) {
    SceneAsset a = single(triangle());
    Camera cam;
    cam.yfov = 0.5f;
    a.cameras.push_back(cam);
    Node n;
    n.camera = 0;
    n.translation = {0, 1, 4};
    n.rotation = glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0));
    n.scale = {3, 0.5f, 2};
    a.nodes.push_back(n);
    a.roots.push_back(1);
    const Scene s = flatten(a, {});
    EXPECT_FALSE(s.default_camera);
    EXPECT_EQ(s.camera.yfov, 0.5f);
    expect_near(s.camera.position, {0, 1, 4});
    const glm::mat3 r = glm::mat3_cast(n.rotation);
    expect_near(s.camera.right, r[0]);
    expect_near(s.camera.up, r[1]);
    expect_near(s.camera.forward, -r[2]);
}

TEST(Flatten, CameraOptionPicksTheCameraInDepthFirstOrder) {
    SceneAsset a = single(triangle());
    a.cameras.resize(2);
    // Node 1 (root) has child node 2 carrying camera 1; node 3 (a later root) carries camera 0.
    Node n1, n2, n3;
    n1.translation = {0, 0, 10};
    n1.children = {2};
    n2.camera = 1;
    n3.camera = 0;
    n3.translation = {0, 0, 20};
    a.nodes.insert(a.nodes.end(), {n1, n2, n3});
    a.roots = {0, 1, 3};
    expect_near(flatten(a, {}).camera.position, {0, 0, 10});   // -1: the first camera met
    FlattenOptions o;
    o.camera = 0;
    expect_near(flatten(a, o).camera.position, {0, 0, 20});
    o.camera = 5;
    EXPECT_THROW(flatten(a, o), std::out_of_range);
}

// ---------------------------------------------------------------------------------------------------------------

TEST(AnimationSampling, LinearTranslationAtMidpoint) {
    AnimationChannel c;
    c.path = AnimationPath::Translation;
    c.interpolation = Interpolation::Linear;
    c.times = {1.0f, 3.0f};
    c.values = {{0, 0, 0, 0}, {4, 2, -2, 0}};
    const SceneAsset a = animated(c);
    expect_near(evaluated_node(a, 2.0f).translation, {2, 1, -1});
    expect_near(evaluated_node(a, 2.5f).translation, {3, 1.5f, -1.5f});
    // Clamped outside the key range.
    expect_near(evaluated_node(a, 0.0f).translation, {0, 0, 0});
    expect_near(evaluated_node(a, 9.0f).translation, {4, 2, -2});
    EXPECT_EQ(a.animations[0].duration(), 3.0f);
}

TEST(AnimationSampling, RotationUsesSlerp) {
    AnimationChannel c;
    c.path = AnimationPath::Rotation;
    c.interpolation = Interpolation::Linear;
    c.times = {0.0f, 1.0f};
    c.values = {xyzw(glm::quat(1, 0, 0, 0)), xyzw(glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0)))};
    SceneAsset a = animated(c);
    a.meshes[0].primitives[0].positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    FlattenOptions o;
    o.time = 0.5f;
    const Scene s = flatten(a, o);
    // Halfway is 45 degrees about Y; (1,0,0) -> (cos45, 0, -sin45). A plain lerp + normalize gives the same
    // direction here, so also check a quarter: 22.5 degrees.
    const float r = std::sqrt(0.5f);
    expect_near(s.positions[0], {r, 0, -r});
    o.time = 0.25f;
    const glm::vec3 q = flatten(a, o).positions[0];
    expect_near(q, {std::cos(glm::radians(22.5f)), 0, -std::sin(glm::radians(22.5f))});
}

TEST(AnimationSampling, RotationSlerpTakesTheShortArc) {
    AnimationChannel c;
    c.path = AnimationPath::Rotation;
    c.interpolation = Interpolation::Linear;
    c.times = {0.0f, 1.0f};
    // The same 90 degree target with a negated quaternion: still the 45 degree halfway point.
    c.values = {xyzw(glm::quat(1, 0, 0, 0)), -xyzw(glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0)))};
    SceneAsset a = animated(c);
    a.meshes[0].primitives[0].positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    FlattenOptions o;
    o.time = 0.5f;
    const float r = std::sqrt(0.5f);
    expect_near(flatten(a, o).positions[0], {r, 0, -r});
}

TEST(AnimationSampling, StepHoldsThePreviousKey) {
    AnimationChannel c;
    c.path = AnimationPath::Translation;
    c.interpolation = Interpolation::Step;
    c.times = {0.0f, 1.0f, 2.0f};
    c.values = {{0, 0, 0, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}};
    const SceneAsset a = animated(c);
    expect_near(evaluated_node(a, 0.99f).translation, {0, 0, 0});
    expect_near(evaluated_node(a, 1.0f).translation, {1, 0, 0});
    expect_near(evaluated_node(a, 1.5f).translation, {1, 0, 0});
    expect_near(evaluated_node(a, 5.0f).translation, {2, 0, 0});
}

TEST(AnimationSampling, CubicSplineAtKeysEqualsKeyValuesAndFollowsHermite) {
    AnimationChannel c;
    c.path = AnimationPath::Translation;
    c.interpolation = Interpolation::CubicSpline;
    c.times = {0.0f, 2.0f};
    // in-tangent, value, out-tangent per key.
    c.values = {{9, 9, 9, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 0}, {4, 0, 0, 0}, {-9, -9, -9, 0}};
    const SceneAsset a = animated(c);
    expect_near(evaluated_node(a, 0.0f).translation, {0, 0, 0});
    expect_near(evaluated_node(a, 2.0f).translation, {4, 0, 0});
    // s = 0.5, dt = 2: 0.5 * 0 + dt * 0.125 * 1 + 0.5 * 4 + dt * (-0.125) * 0 = 2.25.
    expect_near(evaluated_node(a, 1.0f).translation, {2.25f, 0, 0});
}

TEST(AnimationSampling, MismatchedChannelIsIgnored) {
    AnimationChannel c;
    c.path = AnimationPath::Translation;
    c.times = {0.0f, 1.0f};
    c.values = {{5, 5, 5, 0}};
    expect_near(evaluated_node(animated(c), 0.5f).translation, {0, 0, 0});
}

TEST(AnimationSampling, DurationIsTheLastKeyOfAnyChannel) {
    Animation a;
    EXPECT_EQ(a.duration(), 0.0f);
    AnimationChannel c1, c2;
    c1.times = {0.0f, 1.5f};
    c2.times = {0.5f, 2.5f};
    a.channels = {c1, c2};
    EXPECT_EQ(a.duration(), 2.5f);
}

TEST(DefaultLight, EmptyBoundsGiveAFiniteLight) {
    const Light l = default_light(Bounds{});
    EXPECT_GT(l.intensity, 0.0f);
    EXPECT_TRUE(std::isfinite(l.position.x + l.position.y + l.position.z));
    const Camera c = default_camera(Bounds{}, 0.0f);
    EXPECT_TRUE(std::isfinite(c.position.x + c.position.y + c.position.z));
    EXPECT_NEAR(c.yfov, glm::radians(45.0f), 1e-6f);
}

Bounds cube(float lo, float hi) {
    Bounds b;
    b.add(glm::vec3(lo));
    b.add(glm::vec3(hi));
    return b;
}

TEST(WorkingRange, ScenesFromATenBillionthToTenBillionUnitsAcrossPass) {
    EXPECT_EQ(working_range_problem(cube(-1.0f, 1.0f)), "");
    EXPECT_EQ(working_range_problem(cube(0.0f, 1e-10f)), "");
    EXPECT_EQ(working_range_problem(cube(-1e9f, 1e9f)), "");
    EXPECT_EQ(working_range_problem(Bounds{}), "");   // no triangles: nothing to say
}

TEST(WorkingRange, TinyHugeAndFarAwayScenesAreNamedWithTheirSize) {
    EXPECT_NE(working_range_problem(cube(0.0f, 1e-16f)).find("1.73e-16 units across: below 1e-10"), std::string::npos);
    EXPECT_NE(working_range_problem(cube(-1e15f, 1e15f)).find("beyond 1e+10"), std::string::npos);
    // A small scene far from the origin: its coordinates are past the range though its size is not.
    EXPECT_NE(working_range_problem(cube(1e12f, 1e12f + 1e6f)).find("from the origin"), std::string::npos);
    // Extents whose squares overflow a float are measured in double, not as Inf.
    EXPECT_EQ(working_range_problem(cube(-3e38f, 3e38f)).find("inf"), std::string::npos);
}

}  // namespace
}  // namespace rt
