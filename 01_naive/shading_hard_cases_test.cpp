// Shading's hard cases beyond common/trace/shading_test.cpp (shading.h, whitted.h) on hits found by stage 01's
// brute-force tracer: refraction through a tessellated glass sphere (a ray leaves like the smooth sphere's, which
// common/trace/refraction_test.cpp checks on refract_dir alone) and shading normals facing away from the ray.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/scene/scene.h"
#include "common/trace/hard_cases.h"
#include "common/trace/intersect.h"
#include "common/trace/shading.h"
#include "common/trace/whitted.h"

namespace rt {
namespace {

using namespace hard_cases;   // the meshes, rays and placements shared with the GLSL suite

// The smooth sphere of common/trace/refraction_test.cpp, tessellated, through the tracer, surface_point and Whitted's
// choice of eta: entering, the hit is a front face (eta = 1/ior); leaving, a back face (eta = ior). Interpolated
// normals on a 96 x 48 sphere differ from the smooth sphere's by less than the facet angle (2 pi / 96 = 0.065 rad)
// squared, and the ray's path by about as much.
TEST(Refraction, ARayThroughATessellatedGlassSphereLeavesLikeTheSmoothOne) {
    const Scene s = flatten_without_light(asset_of({make_uv_sphere({0, 0, 0}, 1.0f, 96, 48, 0)}));
    const BruteForceTracer<float> tracer(s, IntersectMethod::Watertight);
    RayCounters counters;
    const float ior = 1.5f;
    for (float h : {0.05f, 0.3f, 0.6f, 0.85f}) {
        Ray<float> ray;
        ray.origin = glm::vec3(0.13f, h, 3.0f);   // off the seam and the pole, towards -z
        ray.direction = glm::vec3(0, 0, -1);
        const float r = std::sqrt(h * h + 0.13f * 0.13f);   // distance from the sphere's axis along the ray
        Hit<float> entry_hit, exit_hit;
        ASSERT_TRUE(tracer.closest(ray, entry_hit, counters));
        const SurfacePoint<float> entry = surface_point(s, ray, entry_hit);
        EXPECT_TRUE(entry.front_face);
        Ray<float> inside;
        const float eta_in = entry.front_face ? 1 / ior : ior;   // as Whitted chooses it
        ASSERT_TRUE(refract_dir(ray.direction, entry.shading_normal, eta_in, inside.direction));
        inside.origin =
            offset_ray_origin(OffsetMethod::Robust, entry.position, entry.geometric_normal, inside.direction);
        ASSERT_TRUE(tracer.closest(inside, exit_hit, counters));
        const SurfacePoint<float> exit = surface_point(s, inside, exit_hit);
        EXPECT_FALSE(exit.front_face) << "leaving the solid, the hit must be a back face";
        EXPECT_LT(glm::dot(exit.shading_normal, glm::normalize(exit.position)), 0.0f) << "normal must face the ray";
        glm::vec3 out;
        ASSERT_TRUE(refract_dir(inside.direction, exit.shading_normal, exit.front_face ? 1 / ior : ior, out));
        // Smooth sphere: the ray leaves at the angle it came in (sin = r to the normal) and is deviated by
        // 2 (theta_i - theta_t) towards the axis, in the plane of the ray and the centre.
        const float deviation = std::acos(std::clamp(glm::dot(out, ray.direction), -1.0f, 1.0f));
        const float expected = 2.0f * (std::asin(r) - std::asin(r / ior));
        EXPECT_NEAR(deviation, expected, 0.0065f) << "h = " << h;   // a tenth of the facet angle
        EXPECT_NEAR(glm::length(glm::cross(out, glm::normalize(exit.position))), r, 0.0065f) << "h = " << h;
    }
}

TEST(ShadingNormals, NormalsFacingAwayFromTheRayAreTurnedTowardsIt) {
    // Vertex normals pointing to -z, the back of a triangle seen from +z (as happens near silhouettes of meshes with
    // interpolated normals, or with normals flipped in the file).
    const Scene s = lit_triangle({0, 0, -1});
    const BruteForceTracer<float> tracer(s, IntersectMethod::Watertight);
    RayCounters counters;
    for (float side : {1.0f, -1.0f}) {
        const Ray<float> ray{{0.1f, 0.0f, 2.0f * side}, {0, 0, -side}};
        Hit<float> hit;
        ASSERT_TRUE(tracer.closest(ray, hit, counters));
        const SurfacePoint<float> sp = surface_point(s, ray, hit);
        EXPECT_EQ(sp.front_face, side > 0);
        EXPECT_EQ(sp.geometric_normal, Vec3<float>(0, 0, side)) << "the geometric normal faces the ray";
        EXPECT_EQ(sp.shading_normal, glm::vec3(0, 0, side)) << "the shading normal is turned to the ray's side";
    }
    // So the lit side of a triangle with flipped normals is lit, not left in its ambient term.
    WhittedSettings ws;
    ws.effects = analyze_effects(s);
    const Whitted<float, BruteForceTracer<float>> whitted(s, tracer, ws);
    const glm::vec3 c = whitted.radiance(Ray<float>{{0.1f, 0.0f, 2.0f}, {0, 0, -1}}, 0, glm::vec3(1), counters);
    EXPECT_GT(c.x, 10.0f * kAmbient);
    // And it shades exactly like the same triangle with correct normals.
    const Scene correct = lit_triangle({0, 0, 1});
    const BruteForceTracer<float> correct_tracer(correct, IntersectMethod::Watertight);
    const Whitted<float, BruteForceTracer<float>> correct_whitted(correct, correct_tracer, ws);
    EXPECT_EQ(c, correct_whitted.radiance(Ray<float>{{0.1f, 0.0f, 2.0f}, {0, 0, -1}}, 0, glm::vec3(1), counters));
}

}  // namespace
}  // namespace rt
