// The whole integrator (whitted.h) with stage 01's brute-force tracer on inputs that must not break it: degenerate
// triangles, NaN/Inf vertices and NaN/zero ray directions give no crash, no hang and no NaN or Inf pixel (by hand and
// through a glTF file); and builtin:far (the Whitted scene moved by 1e4) renders like builtin:whitted with the robust
// offset, while a fixed epsilon shows acne there. Every render is checked for non-finite pixels; the golden tests do
// the same for every stage (tests/run_golden.cmake renders an EXR and tests/image_compare fails on any non-finite
// pixel). The ray/triangle tests alone on the same broken inputs: common/trace/intersect_inputs_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/app/image.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/scene/gltf/gltf_io.h"
#include "common/scene/scene.h"
#include "common/trace/hard_cases.h"
#include "common/trace/intersect.h"
#include "common/trace/offset.h"
#include "common/trace/shading.h"
#include "common/trace/whitted.h"

namespace rt {
namespace {

using namespace hard_cases;   // the meshes, rays and placements shared with the GLSL suite

// A scene with every broken triangle (as a hand-made Scene would have them; flatten drops the non-finite ones) in
// front of one valid triangle.
Scene scene_with_broken_triangles() {
    Scene s = lit_triangle({0, 0, 1});
    for (const TriangleCase<float>& tri : broken_triangles<float>()) {
        for (const glm::vec3& p : {tri.a, tri.b, tri.c}) s.positions.push_back(p + glm::vec3(0, 0, 0.5f));
        s.normals.insert(s.normals.end(), {glm::vec3(0, 0, 1), glm::vec3(kNaN), glm::vec3(kInf, 0, 0)});
        s.uvs.insert(s.uvs.end(), {glm::vec2(kNaN), glm::vec2(kInf), glm::vec2(0)});
        s.material_ids.push_back(0);
    }
    return s;
}

TEST(Inputs, BruteForceTracerFindsTheValidTriangleBehindBrokenOnes) {
    const Scene s = scene_with_broken_triangles();
    for (IntersectMethod m : kMethods) {
        const BruteForceTracer<float> tracer(s, m);
        RayCounters counters;
        for (const glm::vec3 origin : {glm::vec3(0.2f, 0.3f, 2.0f), glm::vec3(0.2f, 0.2f, 2.0f), glm::vec3(0, 0, 2)}) {
            const Ray<float> ray{origin, {0, 0, -1}};
            Hit<float> hit;
            ASSERT_TRUE(tracer.closest(ray, hit, counters)) << name_of(m);
            EXPECT_EQ(hit.triangle, 0) << name_of(m);
            EXPECT_FLOAT_EQ(hit.t, 2.0f) << name_of(m);
            EXPECT_TRUE(tracer.occluded(ray, counters)) << name_of(m);
        }
        for (const auto& [name, ray] : broken_rays<float>()) {
            Hit<float> hit;
            EXPECT_FALSE(tracer.closest(ray, hit, counters)) << name_of(m) << ": " << name;
            EXPECT_FALSE(tracer.occluded(ray, counters)) << name_of(m) << ": " << name;
        }
    }
}

TEST(Inputs, WhittedGivesFinitePixelsForBrokenRaysAndTriangles) {
    // The whole integrator (shadow, reflection and refraction rays) on the Whitted scene with broken rays: the
    // background comes back, nothing hangs.
    const Scene whitted_scene = flatten(make_builtin_scene("whitted"), FlattenOptions{});
    for (IntersectMethod m : kMethods) {
        const BruteForceTracer<float> tracer(whitted_scene, m);
        WhittedSettings ws;
        ws.effects = analyze_effects(whitted_scene);
        const Whitted<float, BruteForceTracer<float>> whitted(whitted_scene, tracer, ws);
        RayCounters counters;
        for (const auto& [name, ray] : broken_rays<float>()) {
            const glm::vec3 c = whitted.radiance(ray, 0, glm::vec3(1), counters);
            EXPECT_EQ(c, whitted_scene.background) << name_of(m) << ": " << name;
        }
    }
    // Degenerate triangles and NaN/Inf vertices, normals and UVs in the scene: every pixel finite, in both precisions
    // and with every knob.
    const Scene broken = scene_with_broken_triangles();
    for (IntersectMethod m : kMethods)
        for (OffsetMethod o : kOffsets) {
            WhittedSettings ws;
            ws.offset = o;
            ws.effects = Effects{true, true, true, true};
            const BruteForceTracer<float> tf(broken, m);
            const BruteForceTracer<double> td(broken, m);
            const Whitted<float, BruteForceTracer<float>> wf(broken, tf, ws);
            const Whitted<double, BruteForceTracer<double>> wd(broken, td, ws);
            RayCounters counters;
            std::size_t non_finite = 0;
            for (int y = 0; y < 16; ++y)
                for (int x = 0; x < 16; ++x) {
                    const glm::vec3 o1(-1.2f + 0.15f * float(x), -1.2f + 0.15f * float(y), 2.0f);
                    const glm::vec3 cf = wf.radiance(Ray<float>{o1, glm::normalize(glm::vec3(0.05f, 0.02f, -1))}, 0,
                                                     glm::vec3(1), counters);
                    const glm::vec3 cd = wd.radiance(Ray<double>{o1, glm::normalize(glm::dvec3(0.05, 0.02, -1))}, 0,
                                                     glm::vec3(1), counters);
                    non_finite += !all_finite(cf) + !all_finite(cd);
                }
            EXPECT_EQ(non_finite, 0u) << name_of(m) << ", " << name_of(o);
        }
}

// Renders a flattened scene with the Whitted integrator and the brute-force tracer (two threads, pixel centres).
template <class T>
Image render(const Scene& s, const WhittedSettings& ws, IntersectMethod method, int width, int height) {
    const BruteForceTracer<T> tracer(s, method);
    const Whitted<T, BruteForceTracer<T>> whitted(s, tracer, ws);
    Image image(width, height);
    auto rows = [&](int first) {
        RayCounters counters;
        for (int y = first; y < height; y += 2)
            for (int x = 0; x < width; ++x)
                image.at(x, y) = whitted.radiance(camera_ray<T>(s.camera, width, height, T(x) + T(0.5), T(y) + T(0.5)),
                                                  0, glm::vec3(1), counters);
    };
    std::thread odd(rows, 1);
    rows(0);
    odd.join();
    return image;
}

std::string test_output_dir() {
    const std::filesystem::path dir = std::filesystem::path(RT_TEST_OUTPUT_DIR) / "hard_cases";
    std::filesystem::create_directories(dir);
    return dir.string();
}

TEST(Inputs, AGltfSceneWithDegenerateAndNonFiniteTrianglesRendersWithoutNaNOrInfPixels) {
    // The Whitted scene plus one mesh of broken triangles in front of the camera: degenerate ones (zero area: three
    // equal vertices, two equal, collinear) and ones with NaN/Inf positions, and a valid triangle with NaN/Inf
    // normals and UVs. Written as glTF, read back, flattened and rendered like any file a student might load.
    SceneAsset asset = make_builtin_scene("whitted");
    Primitive broken;
    broken.material = 1;   // glass: reflection and refraction rays through the broken triangles too
    const glm::vec3 o(0.0f, 1.2f, 2.5f);   // between the camera and the spheres
    broken.positions = {o, o, o,                                                        // three equal vertices
                        o, o + glm::vec3(0.5f, 0, 0), o + glm::vec3(0.5f, 0, 0),        // two equal
                        o, o + glm::vec3(0.3f, 0.1f, 0), o + glm::vec3(0.9f, 0.3f, 0),  // collinear
                        o, o + glm::vec3(1, 0, 0), glm::vec3(kNaN, 1, 2.5f),            // NaN position
                        o, glm::vec3(kInf, 1, 2.5f), o + glm::vec3(0, 1, 0),            // +Inf position
                        o, glm::vec3(0, -kInf, 2.5f), o + glm::vec3(0, -1, 0),          // -Inf position
                        o + glm::vec3(-1, -0.4f, 0), o + glm::vec3(-0.6f, -0.4f, 0), o + glm::vec3(-0.8f, -0.1f, 0)};
    broken.normals.assign(broken.positions.size(), glm::vec3(0, 0, 1));
    broken.uvs.assign(broken.positions.size(), glm::vec2(0.5f));
    broken.normals[18] = glm::vec3(kNaN);                // the valid triangle's normals and UVs are broken
    broken.normals[19] = glm::vec3(kInf, 0, 0);
    broken.normals[20] = glm::vec3(0.0f);
    broken.uvs[18] = glm::vec2(kNaN);
    broken.uvs[19] = glm::vec2(-kInf);
    Mesh mesh;
    mesh.name = "broken triangles";
    mesh.primitives.push_back(broken);
    asset.meshes.push_back(mesh);
    Node node;
    node.name = "broken triangles";
    node.mesh = int(asset.meshes.size() - 1);
    asset.nodes.push_back(node);
    asset.roots.push_back(int(asset.nodes.size() - 1));

    const std::string dir = test_output_dir();
    const std::string path = dir + "/broken_triangles.gltf";
    save_gltf(asset, path);
    const SceneAsset loaded = load_gltf(path);
    FlattenOptions fo;
    fo.aspect = 4.0f / 3.0f;
    std::size_t dropped = 0;
    const Scene s = flatten(loaded, fo, &dropped);
    EXPECT_EQ(dropped, 3u) << "flatten drops exactly the triangles with a non-finite vertex";
    EXPECT_EQ(s.triangle_count(), flatten(make_builtin_scene("whitted"), fo).triangle_count() + 4);

    WhittedSettings ws;
    ws.effects = analyze_effects(s);
    for (IntersectMethod m : kMethods)
        for (OffsetMethod off : kOffsets) {
            ws.offset = off;
            const Image image = render<float>(s, ws, m, 32, 24);
            EXPECT_EQ(count_non_finite(image), 0u) << name_of(m) << ", " << name_of(off);
            // Through an EXR file as the golden-image tests check it (a float image keeps NaN and Inf).
            const std::string exr = dir + "/broken_triangles_" + name_of(m) + "_" + name_of(off) + ".exr";
            write_image(exr, image);
            EXPECT_EQ(count_non_finite(read_image(exr)), 0u) << exr;
        }
    const Image d = render<double>(s, ws, IntersectMethod::Watertight, 32, 24);
    EXPECT_EQ(count_non_finite(d), 0u) << "double";
}

// The far scene.

// Fraction of pixels where some channel differs by more than `threshold` once both images are encoded as 8-bit sRGB,
// as the golden-image comparison does (tests/image_compare.cpp: threshold 0.016, at most 1% of pixels).
double fraction_differing(const Image& a, const Image& b, float threshold = 0.016f) {
    auto encode = [](float v) { return float(std::lround(linear_to_srgb(v) * 255.0f)) / 255.0f; };
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (std::abs(encode(a.pixels[i][c]) - encode(b.pixels[i][c])) > threshold) {
                ++differing;
                break;
            }
    return double(differing) / double(a.pixels.size());
}

constexpr int kFarWidth = 64, kFarHeight = 48;

Image render_builtin(const std::string& name, OffsetMethod offset) {
    FlattenOptions fo;
    fo.aspect = float(kFarWidth) / float(kFarHeight);
    const Scene s = flatten(make_builtin_scene(name), fo);
    WhittedSettings ws;
    ws.offset = offset;
    ws.effects = analyze_effects(s);
    Image image = render<float>(s, ws, IntersectMethod::Watertight, kFarWidth, kFarHeight);
    EXPECT_EQ(count_non_finite(image), 0u) << name << ", " << name_of(offset);
    return image;
}

const Image& whitted_reference() {
    static const Image image = render_builtin("whitted", OffsetMethod::Robust);
    return image;
}

TEST(FarScene, RendersLikeWhittedWithTheRobustOffset) {
    const double differing = fraction_differing(render_builtin("far", OffsetMethod::Robust), whitted_reference());
    std::printf("[ far ] builtin:far vs builtin:whitted, %dx%d, float, robust offset: %.2f%% of pixels differ by more "
                "than 0.016 (golden limit 1%%)\n", kFarWidth, kFarHeight, 100 * differing);
    RecordProperty("differing_percent", std::to_string(100 * differing));
    EXPECT_LT(differing, 0.01);
}

TEST(FarScene, AFixedEpsilonShowsAcneThereButNotNearTheOrigin) {
    const double far = fraction_differing(render_builtin("far", OffsetMethod::Epsilon), whitted_reference());
    const double near = fraction_differing(render_builtin("whitted", OffsetMethod::Epsilon), whitted_reference());
    std::printf("[ far ] epsilon offset, %dx%d, float: builtin:far differs from builtin:whitted in %.2f%% of pixels "
                "(acne), builtin:whitted itself in %.2f%%\n", kFarWidth, kFarHeight, 100 * far, 100 * near);
    RecordProperty("far_differing_percent", std::to_string(100 * far));
    EXPECT_GT(far, 0.05) << "at 1e4 the 1e-4 epsilon is below a float step: acne on every surface";
    EXPECT_LT(near, 0.01) << "near the origin the epsilon works";
}

}  // namespace
}  // namespace rt
