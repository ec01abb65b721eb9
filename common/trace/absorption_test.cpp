// Absorption (absorption.h), texture transforms (texture_transform.h) and normal-map decoding (normal_map.h): the
// values docs/shading.md states.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "absorption.h"
#include "normal_map.h"
#include "texture_transform.h"

namespace rt {
namespace {

Material absorbing(glm::vec3 color, float distance) {
    Material m;
    m.metallic = 0.0f;
    m.transmission = 1.0f;
    m.thickness = 1.0f;
    m.attenuation_color = color;
    m.attenuation_distance = distance;
    return m;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TEST(Absorption, BeerLambertKeepsTheAttenuationColourAfterTheAttenuationDistance) {
    const Material m = absorbing({0.5f, 0.25f, 1.0f}, 2.0f);
    const glm::vec3 sigma = absorption_coefficient(m);
    EXPECT_FLOAT_EQ(sigma.x, std::log(2.0f) / 2.0f);
    EXPECT_FLOAT_EQ(sigma.z, 0.0f);   // a white channel does not absorb
    const glm::vec3 at_d = transmittance(sigma, 2.0f);    // c^(t/d) with t = d: c
    EXPECT_NEAR(at_d.x, 0.5f, 1e-6f);
    EXPECT_NEAR(at_d.y, 0.25f, 1e-6f);
    EXPECT_EQ(at_d.z, 1.0f);
    const glm::vec3 at_2d = transmittance(sigma, 4.0f);   // twice as far: c^2
    EXPECT_NEAR(at_2d.x, 0.25f, 1e-6f);
    EXPECT_NEAR(at_2d.y, 0.0625f, 1e-6f);
    EXPECT_EQ(transmittance(sigma, 0.0f), glm::vec3(1.0f));
}

TEST(Absorption, ThinWalledOpaqueAndInfinitelyClearMaterialsDoNotAbsorb) {
    Material thin = absorbing({0.5f, 0.5f, 0.5f}, 1.0f);
    thin.thickness = 0.0f;
    EXPECT_FALSE(material_absorbs(thin));
    EXPECT_EQ(absorption_coefficient(thin), glm::vec3(0.0f));
    Material opaque = absorbing({0.5f, 0.5f, 0.5f}, 1.0f);
    opaque.transmission = 0.0f;
    EXPECT_FALSE(material_absorbs(opaque));
    const Material clear = absorbing({0.5f, 0.5f, 0.5f}, std::numeric_limits<float>::infinity());
    EXPECT_FALSE(material_absorbs(clear));
    EXPECT_EQ(absorption_coefficient(clear), glm::vec3(0.0f));
    EXPECT_TRUE(material_absorbs(absorbing({0.5f, 0.5f, 0.5f}, 1.0f)));
}

TEST(Absorption, BlackColourAndTinyDistanceGiveNoNaN) {
    for (const float d : {1.0f, std::numeric_limits<float>::min(), std::numeric_limits<float>::denorm_min()}) {
        const glm::vec3 sigma = absorption_coefficient(absorbing({0.0f, 1e-30f, 1.0f}, d));
        EXPECT_TRUE(finite(sigma)) << d;
        EXPECT_EQ(transmittance(sigma, 0.0f), glm::vec3(1.0f)) << d;   // 0 * max float = 0: nothing travelled
        const glm::vec3 far = transmittance(sigma, 1e30f);
        EXPECT_TRUE(finite(far)) << d;
        EXPECT_EQ(far.x, 0.0f) << d;
        EXPECT_EQ(far.z, 1.0f) << d;
    }
}

TEST(TextureTransform, IdentityGivesUvBackExactly) {
    const TextureTransform identity;
    for (const glm::vec2 uv : {glm::vec2(0.3f, -7.25f), glm::vec2(1e7f, 3e-12f), glm::vec2(-0.0f, 0.0f)})
        EXPECT_EQ(transform_uv(identity, uv), uv);
}

TEST(TextureTransform, OffsetRotationScaleFollowGltfTRS) {
    TextureTransform t;
    t.offset = {0.5f, 0.25f};
    t.scale = {2.0f, 3.0f};
    t.rotation = 1.5707963f;   // pi/2: R = [0 1; -1 0]
    // S: (1, 1) -> (2, 3); R: (3, -2); T: (3.5, -1.75).
    const glm::vec2 uv = transform_uv(t, {1.0f, 1.0f});
    EXPECT_NEAR(uv.x, 3.5f, 1e-6f);
    EXPECT_NEAR(uv.y, -1.75f, 1e-6f);
}

TEST(NormalMap, DecodesFlatAndScaledTexels) {
    EXPECT_EQ(decode_normal_texel({0.5f, 0.5f, 1.0f}, 1.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    const glm::vec3 tilted = decode_normal_texel({1.0f, 0.0f, 0.5f}, 0.5f);
    EXPECT_EQ(tilted, glm::vec3(0.5f, -0.5f, 0.0f));   // x and y scaled, z not
}

TEST(NormalMap, TangentFrameIsRightHandedAndWFlipsTheBitangent) {
    const glm::vec3 n(0, 0, 1);
    glm::vec3 out;
    ASSERT_TRUE(tangent_to_world(n, {1, 0, 0, 1}, {0, 0, 1}, out));
    EXPECT_EQ(out, n);                                              // the flat texel keeps the normal
    ASSERT_TRUE(tangent_to_world(n, {1, 0, 0, 1}, {0, 1, 0}, out));
    EXPECT_EQ(out, glm::vec3(0, 1, 0));                             // b = cross(n, t) = +Y
    ASSERT_TRUE(tangent_to_world(n, {1, 0, 0, -1}, {0, 1, 0}, out));
    EXPECT_EQ(out, glm::vec3(0, -1, 0));                            // w = -1: mirrored
    // A tangent not orthogonal to n is made so (Gram-Schmidt) before use.
    ASSERT_TRUE(tangent_to_world(n, {2, 0, 5, 1}, {1, 0, 0}, out));
    EXPECT_EQ(out, glm::vec3(1, 0, 0));
}

TEST(NormalMap, DegenerateFramesAreRefused) {
    glm::vec3 out(7.0f);
    EXPECT_FALSE(tangent_to_world({0, 0, 1}, {0, 0, 3, 1}, {0, 0, 1}, out));          // tangent along n
    EXPECT_FALSE(tangent_to_world({0, 0, 1}, {1, 0, 0, 1}, {0, 0, 0}, out));          // zero texel direction
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(tangent_to_world({0, 0, 1}, {nan, 0, 0, 1}, {0, 0, 1}, out));
    EXPECT_EQ(out, glm::vec3(7.0f));
}

}  // namespace
}  // namespace rt
