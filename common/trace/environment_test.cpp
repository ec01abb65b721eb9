// The environment lookup (environment.h, docs/shading.md "The environment"): the mapping's fixed directions, the
// rotation, the atan2 polynomial's accuracy, bilinear filtering with wrap in u and clamp in v, and the background
// when there is no map.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "environment.h"
#include "shading.h"

namespace rt {
namespace {

// A map whose texel (x, y) holds (x, y, 1): a lookup tells where it read.
Environment coordinate_map(int width, int height, float degrees = 0.0f) {
    Environment e;
    e.width = width;
    e.height = height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) e.texels.push_back({float(x), float(y), 1.0f, 1.0f});
    const float radians = degrees * (kPi / 180.0f);
    e.rotation = {std::cos(radians), std::sin(radians)};
    return e;
}

TEST(EnvironmentAtan2, WithinTwelveMillionthsOfARadianEverywhere) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> any(-10.0f, 10.0f);
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const float y = any(rng), x = any(rng);
        worst = std::max(worst, std::fabs(double(environment_atan2(y, x)) - std::atan2(double(y), double(x))));
    }
    EXPECT_LT(worst, 1.2e-5);   // A&S 4.4.47's 1e-5, plus float rounding
    // The axes are exact up to the float constant pi.
    EXPECT_EQ(environment_atan2(0.0f, 1.0f), 0.0f);
    EXPECT_EQ(environment_atan2(1.0f, 0.0f), 0.5f * kPi);
    EXPECT_EQ(environment_atan2(0.0f, -1.0f), kPi);
    EXPECT_EQ(environment_atan2(-1.0f, 0.0f), -0.5f * kPi);
    EXPECT_EQ(environment_atan2(0.0f, 0.0f), 0.0f);
}

TEST(EnvironmentUv, MinusZIsTheCentreUGrowsTowardsPlusXAndVIsZeroStraightUp) {
    const glm::vec2 none(1.0f, 0.0f);
    EXPECT_NEAR(environment_uv({0, 0, -1}, none).x, 0.5f, 1e-6f);
    EXPECT_NEAR(environment_uv({0, 0, -1}, none).y, 0.5f, 1e-6f);
    EXPECT_NEAR(environment_uv({1, 0, 0}, none).x, 0.75f, 1e-6f);
    EXPECT_NEAR(environment_uv({-1, 0, 0}, none).x, 0.25f, 1e-6f);
    EXPECT_NEAR(environment_uv({0, 0, 1}, none).x, 1.0f, 1e-6f);      // the seam: +Z
    EXPECT_NEAR(environment_uv({-1e-6f, 0, 1}, none).x, 0.0f, 1e-6f);  // just past it
    EXPECT_EQ(environment_uv({0, 1, 0}, none).y, 0.0f);
    EXPECT_EQ(environment_uv({0, -1, 0}, none).y, 1.0f);
    EXPECT_NEAR(environment_uv({0, 1, -1}, none).y, 0.25f, 4e-6f);     // 45 degrees up (atan2 error / pi)
    // Length does not matter.
    EXPECT_EQ(environment_uv({0.3f, 0.2f, -0.9f}, none), environment_uv({3.0f, 2.0f, -9.0f}, none));
}

TEST(EnvironmentUv, PositiveRotationTurnsTheMapFromPlusZTowardsPlusX) {
    // Turned by 90 degrees about +Y, what the map had at +Z (the seam) is seen at +X, and what it had at -Z at -X.
    const glm::vec2 quarter(std::cos(0.5f * kPi), std::sin(0.5f * kPi));
    EXPECT_NEAR(std::fmod(environment_uv({1, 0, 0}, quarter).x, 1.0f), 0.0f, 1e-6f);
    EXPECT_NEAR(environment_uv({-1, 0, 0}, quarter).x, 0.5f, 1e-6f);
    EXPECT_NEAR(environment_uv({0, 0, -1}, quarter).x, 0.75f, 1e-6f);   // +X's content is now ahead
    EXPECT_NEAR(environment_uv({0.6f, 0.8f, 0}, quarter).y, environment_uv({0, 0.8f, 0.6f}, {1, 0}).y, 1e-6f);
}

TEST(SampleEnvironment, TexelCentresAreExactAndMidpointsAverage) {
    const Environment e = coordinate_map(8, 4);
    // Centre of texel (3, 2): u = 3.5 / 8, v = 2.5 / 4.
    EXPECT_EQ(sample_environment(e, {3.5f / 8, 2.5f / 4}), glm::vec3(3, 2, 1));
    EXPECT_EQ(sample_environment(e, {4.0f / 8, 2.5f / 4}), glm::vec3(3.5f, 2, 1));
    EXPECT_EQ(sample_environment(e, {4.0f / 8, 2.0f / 4}), glm::vec3(3.5f, 1.5f, 1));
}

TEST(SampleEnvironment, WrapsInUAcrossTheSeamAndClampsInVAtThePoles) {
    const Environment e = coordinate_map(8, 4);
    // u = 0 and u = 1 are the same place: half the last column and half the first.
    EXPECT_EQ(sample_environment(e, {0.0f, 2.5f / 4}), glm::vec3(3.5f, 2, 1));
    EXPECT_EQ(sample_environment(e, {1.0f, 2.5f / 4}), glm::vec3(3.5f, 2, 1));
    // At the poles the top and bottom rows, not their neighbours across.
    EXPECT_EQ(sample_environment(e, {3.5f / 8, 0.0f}), glm::vec3(3, 0, 1));
    EXPECT_EQ(sample_environment(e, {3.5f / 8, 1.0f}), glm::vec3(3, 3, 1));
    // Outside [0, 1] (never from environment_uv) is clamped; NaN gives black, not a NaN pixel.
    EXPECT_EQ(sample_environment(e, {3.5f / 8, 7.0f}), glm::vec3(3, 3, 1));
    EXPECT_EQ(sample_environment(e, {std::nanf(""), 0.5f}), glm::vec3(0.0f));
}

// The default world (docs/shading.md, "Defaults"): grey, 0.9 straight up, 0.6 at the horizon, 0.3 straight down,
// the same all round +Y, monotonic in height, finite and within [nadir, zenith] everywhere.
TEST(DefaultWorld, IsAGreyStudioBrighterAboveThanBelowAndTheSameAllRound) {
    const std::shared_ptr<const Environment> world = default_world();
    ASSERT_TRUE(world);
    EXPECT_EQ(world, default_world());   // one map for the run
    Scene scene;
    scene.environment = world;
    const auto at = [&](const glm::vec3& d) { return miss_radiance(scene, d); };
    EXPECT_NEAR(at({0, 1, 0}).g, kWorldZenith, 1e-3f);
    EXPECT_NEAR(at({0, -1, 0}).g, kWorldNadir, 1e-3f);
    EXPECT_NEAR(at({1, 0, 0}).g, 0.5f * (kWorldZenith + kWorldNadir), 2e-3f);
    float previous = 1e9f;
    for (int k = 0; k <= 180; ++k) {
        const float elevation = glm::radians(90.0f - float(k));
        const glm::vec3 base = at({std::cos(elevation), std::sin(elevation), 0.0f});
        EXPECT_EQ(base.r, base.g);
        EXPECT_EQ(base.g, base.b);
        EXPECT_LE(base.g, previous + 1e-6f);   // darker going down
        EXPECT_GE(base.g, kWorldNadir - 1e-6f);
        EXPECT_LE(base.g, kWorldZenith + 1e-6f);
        previous = base.g;
        for (float azimuth : {0.7f, 2.0f, -2.9f}) {   // the same in every direction around +Y
            const glm::vec3 d(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                              std::cos(elevation) * std::sin(azimuth));
            EXPECT_NEAR(at(d).g, base.g, 1e-6f);
        }
    }
}

TEST(MissRadiance, IsTheBackgroundWithoutAMapAndTheMapWithOne) {
    Scene scene;
    scene.background = {0.1f, 0.2f, 0.3f};
    EXPECT_EQ(miss_radiance(scene, {0, 0, -1}), scene.background);
    scene.environment = std::make_shared<const Environment>(coordinate_map(8, 4));
    // Straight ahead (-Z) is u = 0.5, v = 0.5: between columns 3 and 4, rows 1 and 2.
    EXPECT_EQ(miss_radiance(scene, {0, 0, -1}), glm::vec3(3.5f, 1.5f, 1));
}

}  // namespace
}  // namespace rt
