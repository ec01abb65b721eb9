// Refraction through a whole solid (shading.h): a ray refracted into and out of a smooth glass sphere with
// refract_dir leaves at the angle it entered. The same through a tessellated sphere, with the tracer and Whitted's
// choice of eta: 01_naive/shading_hard_cases_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "shading.h"

namespace rt {
namespace {

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

}  // namespace
}  // namespace rt
