// Shading's hard cases beyond shading_test.cpp (shading.h, whitted.h): refraction through a whole solid (a smooth and
// a tessellated glass sphere: a ray leaves at the angle it entered) and shading normals facing away from the ray.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "01_naive/brute_force_tracer.h"
#include "common/scene/scene.h"
#include "hard_cases.h"
#include "intersect.h"
#include "shading.h"
#include "whitted.h"

namespace rt {
namespace {

using namespace hard_cases;   // the meshes, rays and placements shared with the GLSL suite

// A ray at height h above the axis of a unit glass sphere, refracted in and out with refract_dir. Snell at both
// interfaces and the symmetry of the sphere say: inside, sin(theta_t) = h / 1.5; it leaves at the angle it came in
// (sin = h to the exit normal), in the same plane, deviated by 2 (theta_i - theta_t).
TEST(Refraction, ARayThroughAGlassSphereLeavesAtTheAngleItEntered) {
    const double eta = 1.5;
    for (double h : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
        const glm::vec3 d(1, 0, 0);
        const glm::vec3 entry(float(-std::sqrt(1 - h * h)), float(h), 0);   // on the unit sphere; normal = position
        glm::vec3 inside;
        ASSERT_TRUE(refract_dir(d, entry, float(1 / eta), inside)) << h;
        const double sin_t = h / eta;
        EXPECT_NEAR(glm::length(glm::cross(inside, -entry)), sin_t, 1e-6) << h;
        // Second intersection with the sphere: |entry + s inside| = 1.
        const glm::vec3 exit = entry - 2.0f * glm::dot(entry, inside) * inside;
        glm::vec3 out;
        ASSERT_TRUE(refract_dir(inside, -exit, float(eta), out)) << "no total internal reflection in a sphere: " << h;
        EXPECT_GT(glm::dot(out, exit), 0.0f) << h;
        EXPECT_NEAR(glm::length(glm::cross(out, exit)), h, 2e-6) << h;
        EXPECT_EQ(out.z, 0.0f) << h;
        const double deviation = std::atan2(double(glm::length(glm::cross(d, out))), double(glm::dot(d, out)));
        EXPECT_NEAR(deviation, 2 * (std::asin(h) - std::asin(sin_t)), 1e-5) << h;
    }
}

// The same through a tessellated sphere with the tracer, surface_point and Whitted's choice of eta: entering, the hit
// is a front face (eta = 1/ior); leaving, a back face (eta = ior). Interpolated normals on a 96 x 48 sphere differ
// from the smooth sphere's by less than the facet angle (2 pi / 96 = 0.065 rad) squared, and the ray's path by
// about as much.
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
