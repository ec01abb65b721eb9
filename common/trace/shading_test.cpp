// Shading functions of docs/shading.md: Fresnel, Snell, the material mapping and light falloff.
#include <gtest/gtest.h>

#include "shading.h"
#include "whitted.h"

namespace rt {
namespace {

// The ambient models (docs/shading.md, "Ambient"). Constant is exactly what the built-in scenes' goldens were made
// with; hemisphere runs from 0.4 to 1.6 times it, linear in n.y, and averages to it over the sphere.
TEST(AmbientLight, ConstantIsKAmbientTimesDiffuseToTheBitAndNoneIsZero) {
    const glm::vec3 kd(0.8f, 0.3f, 0.123f), n = glm::normalize(glm::vec3(0.3f, -0.4f, 0.5f));
    EXPECT_EQ(ambient_light(AmbientModel::Constant, kd, n), kAmbient * kd);
    EXPECT_EQ(ambient_light(AmbientModel::None, kd, n), glm::vec3(0.0f));
}

TEST(AmbientLight, HemisphereIsBrighterFacingUpAndAveragesToTheConstantTerm) {
    const glm::vec3 white(1.0f);
    EXPECT_NEAR(ambient_light(AmbientModel::Hemisphere, white, {0, 1, 0}).x, 1.6f * kAmbient, 1e-7f);
    EXPECT_NEAR(ambient_light(AmbientModel::Hemisphere, white, {0, -1, 0}).x, 0.4f * kAmbient, 1e-7f);
    EXPECT_NEAR(ambient_light(AmbientModel::Hemisphere, white, {1, 0, 0}).x, kAmbient, 1e-7f);
    // Over uniformly distributed normals n.y is uniform in [-1, 1]: the mean weight is the one at n.y = 0.
    double sum = 0.0;
    const int steps = 2000;
    for (int k = 0; k < steps; ++k) {
        const float y = -1.0f + 2.0f * (float(k) + 0.5f) / float(steps);
        sum += ambient_light(AmbientModel::Hemisphere, white, {std::sqrt(1.0f - y * y), y, 0.0f}).x;
    }
    EXPECT_NEAR(sum / steps, kAmbient, 1e-6);
}

TEST(Fresnel, NormalIncidenceGlassIsFourPercent) {
    // ((1.5 - 1) / (1.5 + 1))^2 = 0.04, entering glass from air (eta = 1/1.5) and leaving it (eta = 1.5).
    EXPECT_NEAR(fresnel_exact(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnel_exact(1.0f, 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnel_schlick(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnel_exact(1.0, 1.0 / 1.5), 0.04, 1e-12);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
    EXPECT_NEAR(fresnel_exact(0.0f, 1.0f / 1.5f), 1.0f, 1e-6f);
    EXPECT_NEAR(fresnel_schlick(0.0f, 1.0f / 1.5f), 1.0f, 1e-6f);
}

TEST(Fresnel, TotalInternalReflectionIsOne) {
    // Leaving glass (eta = 1.5) beyond the critical angle asin(1/1.5) = 41.8 degrees.
    const float cos_i = std::cos(glm::radians(60.0f));
    EXPECT_EQ(fresnel_exact(cos_i, 1.5f), 1.0f);
    EXPECT_EQ(fresnel_schlick(cos_i, 1.5f), 1.0f);
    glm::vec3 out;
    const glm::vec3 d = glm::normalize(glm::vec3(std::sin(glm::radians(60.0f)), -cos_i, 0.0f));
    EXPECT_FALSE(refract_dir(d, glm::vec3(0, 1, 0), 1.5f, out));
}

TEST(Fresnel, EtaOneReflectsNothing) {
    for (float c : {0.01f, 0.3f, 0.7f, 1.0f}) {
        EXPECT_NEAR(fresnel_exact(c, 1.0f), 0.0f, 1e-6f) << c;
        EXPECT_NEAR(fresnel_schlick(c, 1.0f), 0.0f, 1e-6f) << c;
    }
}

TEST(Fresnel, SchlickStaysCloseToExact) {
    for (float eta : {1.0f / 1.5f, 1.0f / 1.33f, 1.33f, 1.5f})
        for (int i = 0; i <= 100; ++i) {
            const float c = i / 100.0f;
            EXPECT_NEAR(fresnel_schlick(c, eta), fresnel_exact(c, eta), 0.08f) << "eta " << eta << " cos " << c;
        }
}

TEST(Refraction, EnteringAndLeavingASlabRestoresTheDirection) {
    const glm::vec3 d = glm::normalize(glm::vec3(0.6f, -0.8f, 0.0f));
    glm::vec3 inside, outside;
    ASSERT_TRUE(refract_dir(d, glm::vec3(0, 1, 0), 1.0f / 1.5f, inside));
    // Snell: sin_t = sin_i / 1.5.
    EXPECT_NEAR(inside.x, 0.6f / 1.5f, 1e-6f);
    EXPECT_LT(inside.y, 0.0f);
    ASSERT_TRUE(refract_dir(inside, glm::vec3(0, 1, 0), 1.5f, outside));
    EXPECT_NEAR(outside.x, d.x, 1e-6f);
    EXPECT_NEAR(outside.y, d.y, 1e-6f);
}

TEST(Refraction, NormalIncidenceGoesStraightThrough) {
    glm::vec3 out;
    ASSERT_TRUE(refract_dir(glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), 1.0f / 1.5f, out));
    EXPECT_NEAR(out.z, -1.0f, 1e-7f);
}

// glTF's default material is a fully rough metal: no mirror ray, and its reflectance, which Whitted cannot trace as
// a glossy lobe, is diffuse (so a file without materials does not render black).
TEST(Materials, DefaultGltfMaterialIsARoughMetalThatReflectsItsColourDiffusely) {
    const Material m;   // glTF defaults: metallic 1, roughness 1
    const SurfaceCoefficients s = surface_coefficients(m, glm::vec4(1.0f));
    EXPECT_EQ(s.smoothness, 0.0f);
    EXPECT_EQ(s.mirror, glm::vec3(0.0f));
    EXPECT_EQ(s.diffuse, glm::vec3(1.0f));
}

TEST(Materials, AMetalSplitsItsColourBetweenMirrorAndDiffuseBySmoothness) {
    Material m;
    m.base_color = glm::vec4(0.9f, 0.6f, 0.2f, 1.0f);
    for (float roughness : {0.0f, 0.3f, 0.7f, 1.0f}) {
        m.roughness = roughness;
        const SurfaceCoefficients s = surface_coefficients(m, glm::vec4(1.0f));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.mirror[c] + s.diffuse[c], m.base_color[c], 1e-6f) << roughness;
    }
    m.roughness = 0.0f;
    EXPECT_EQ(surface_coefficients(m, glm::vec4(1.0f)).diffuse, glm::vec3(0.0f));   // a perfect mirror stays one
}

TEST(Materials, GlassSplitsIntoFresnelReflectionAndRefraction) {
    Material glass;
    glass.metallic = 0.0f;
    glass.roughness = 0.0f;
    glass.transmission = 1.0f;
    const SurfaceCoefficients s = surface_coefficients(glass, glm::vec4(1.0f));
    const float f = fresnel_exact(1.0f, 1.0f / 1.5f);
    using W = Whitted<float, int>;
    const auto k = W::coefficients(s, true, 1.0f, f);
    EXPECT_NEAR(k.reflection.x, 0.04f, 1e-6f);
    EXPECT_NEAR(k.refraction.x, 0.96f, 1e-6f);
    EXPECT_EQ(s.diffuse, glm::vec3(0.0f));
}

TEST(Materials, SpecularExtensionScalesDielectricReflectance) {
    Material m;
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.specular = 0.5f;
    const SurfaceCoefficients s = surface_coefficients(m, glm::vec4(1.0f));
    EXPECT_NEAR(s.f0_dielectric.x, 0.02f, 1e-6f);
}

TEST(Lights, PointLightFollowsTheInverseSquareLaw) {
    Light l;
    l.intensity = 4.0f;
    l.position = glm::vec3(0, 2, 0);
    glm::vec3 to_light;
    float dist;
    const glm::vec3 e = light_incidence(l, glm::vec3(0), glm::vec3(0, 1, 0), to_light, dist);
    EXPECT_FLOAT_EQ(dist, 2.0f);
    EXPECT_FLOAT_EQ(e.x, 1.0f);   // 4 cd / (2 m)^2 at normal incidence
    EXPECT_EQ(to_light, glm::vec3(0, 1, 0));
}

TEST(Lights, SurfaceFacingAwayGetsNothing) {
    Light l;
    l.position = glm::vec3(0, -1, 0);
    glm::vec3 to_light;
    float dist;
    EXPECT_EQ(light_incidence(l, glm::vec3(0), glm::vec3(0, 1, 0), to_light, dist), glm::vec3(0.0f));
}

TEST(Lights, SpotConeCutsOffOutside) {
    Light l;
    l.type = LightType::Spot;
    l.position = glm::vec3(0, 1, 0);
    l.direction = glm::vec3(0, -1, 0);
    l.inner_cone = 0.1f;
    l.outer_cone = 0.2f;
    glm::vec3 to_light;
    float dist;
    EXPECT_GT(light_incidence(l, glm::vec3(0), glm::vec3(0, 1, 0), to_light, dist).x, 0.0f);
    EXPECT_EQ(light_incidence(l, glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), to_light, dist), glm::vec3(0.0f));
}

TEST(Lights, DirectionalLightIsIrradianceTimesCosine) {
    Light l;
    l.type = LightType::Directional;
    l.intensity = 2.0f;
    l.direction = glm::vec3(0, -1, 0);
    glm::vec3 to_light;
    float dist;
    const glm::vec3 e = light_incidence(l, glm::vec3(5, 0, 5), glm::vec3(0, 1, 0), to_light, dist);
    EXPECT_FLOAT_EQ(e.x, 2.0f);
    EXPECT_TRUE(std::isinf(dist));
}

TEST(Lights, EyeExactlyOppositeTheLightGivesAFiniteHighlight) {
    Material m;
    m.metallic = 0.0f;
    m.roughness = 0.2f;
    const SurfaceCoefficients s = surface_coefficients(m, glm::vec4(1.0f));
    const glm::vec3 n(0, 0, 1), to_light(0, 0, 1), to_eye(0, 0, -1);   // half vector 0
    const glm::vec3 c = shade_light(s, glm::vec3(1.0f), n, to_light, to_eye);
    EXPECT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    EXPECT_NEAR(c.x, s.diffuse.x / kPi, 1e-7f);   // the diffuse term alone
}

TEST(Textures, NearestRepeatsAndDecodesSrgb) {
    Texture t;
    t.width = 2;
    t.height = 1;
    t.nearest = true;
    t.rgba8 = {255, 255, 255, 255, 0, 0, 0, 255};
    EXPECT_FLOAT_EQ(sample_texture(t, {0.25f, 0.5f}).x, 1.0f);
    EXPECT_FLOAT_EQ(sample_texture(t, {0.75f, 0.5f}).x, 0.0f);
    EXPECT_FLOAT_EQ(sample_texture(t, {-0.75f, 0.5f}).x, 1.0f);   // REPEAT for negative coordinates
    EXPECT_FLOAT_EQ(sample_texture(t, {7.25f, 0.5f}).x, 1.0f);
}

TEST(Textures, BilinearBlendsNeighbours) {
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba8 = {255, 255, 255, 255, 0, 0, 0, 255};
    EXPECT_NEAR(sample_texture(t, {0.5f, 0.5f}).x, 0.5f, 1e-6f);   // halfway between the two texel centres
}

TEST(Textures, ClampToEdgeAndMirroredRepeatFoldCoordinatesAsGltfSamplersSay) {
    Texture t;   // texel 0 white, texel 1 black
    t.width = 2;
    t.height = 1;
    t.rgba8 = {255, 255, 255, 255, 0, 0, 0, 255};
    t.nearest = true;
    t.wrap_s = Wrap::ClampToEdge;
    EXPECT_EQ(sample_texture(t, {-0.5f, 0.5f}).x, 1.0f);   // left of the image: its left texel
    EXPECT_EQ(sample_texture(t, {1.5f, 0.5f}).x, 0.0f);    // right of it: its right texel
    EXPECT_EQ(sample_texture(t, {1.0f, 0.5f}).x, 0.0f);    // exactly 1: the last texel, not the first
    t.wrap_s = Wrap::MirroredRepeat;
    EXPECT_EQ(sample_texture(t, {1.25f, 0.5f}).x, 0.0f);   // the second period runs backwards: 0.75
    EXPECT_EQ(sample_texture(t, {1.75f, 0.5f}).x, 1.0f);   // 0.25
    EXPECT_EQ(sample_texture(t, {-0.25f, 0.5f}).x, 1.0f);  // 0.25
    EXPECT_EQ(sample_texture(t, {2.25f, 0.5f}).x, 1.0f);   // the third runs forwards again
    // Bilinear at the left edge: REPEAT blends in the right texel, the other two read the edge texel alone.
    t.nearest = false;
    t.wrap_s = Wrap::Repeat;
    EXPECT_NEAR(sample_texture(t, {0.0f, 0.5f}).x, 0.5f, 1e-6f);
    for (Wrap w : {Wrap::ClampToEdge, Wrap::MirroredRepeat}) {
        t.wrap_s = w;
        EXPECT_EQ(sample_texture(t, {0.0f, 0.5f}).x, 1.0f) << int(w);
        EXPECT_EQ(sample_texture(t, {1.0f, 0.5f}).x, 0.0f) << int(w);
    }
}

TEST(Textures, MetallicRoughnessIsLinearAndEmissiveIsSrgb) {
    Texture mr;   // green 51 (roughness 0.2), blue 255 (metallic 1), read as linear bytes / 255
    mr.width = mr.height = 1;
    mr.rgba8 = {0, 51, 255, 255};
    Texture glow;   // sRGB 188 is about linear 0.5
    glow.width = glow.height = 1;
    glow.rgba8 = {188, 0, 255, 255};
    Material m;
    m.metallic = 0.5f;
    m.roughness = 1.0f;
    m.emissive = glm::vec3(2.0f);
    m.metallic_roughness_texture = 0;
    m.emissive_texture = 1;
    const SurfaceTexels t = sample_surface_textures(m, {mr, glow}, {0.5f, 0.5f});
    EXPECT_EQ(t.roughness, 51.0f / 255.0f);
    EXPECT_EQ(t.metallic, 1.0f);
    EXPECT_EQ(t.emissive, glm::vec3(srgb_to_linear(188.0f / 255.0f), 0.0f, 1.0f));
    const SurfaceCoefficients s = surface_coefficients(m, t);
    EXPECT_FLOAT_EQ(s.smoothness, 0.64f);   // (1 - 0.2)^2: the texture made a rough factor smooth
    EXPECT_EQ(s.dielectric, 0.5f);
    EXPECT_EQ(s.emissive, 2.0f * t.emissive);
}

TEST(Textures, MaterialWithoutExtraTexturesKeepsItsFactorsExactly) {
    Material m;
    m.metallic = 0.3f;
    m.roughness = 0.7f;
    m.emissive = {0.1f, 0.2f, 0.3f};
    const SurfaceCoefficients a = surface_coefficients(m, sample_surface_textures(m, {}, {0.5f, 0.5f}));
    const SurfaceCoefficients b = surface_coefficients(m, glm::vec4(1.0f));
    EXPECT_EQ(a.smoothness, b.smoothness);
    EXPECT_EQ(a.dielectric, 1.0f - 0.3f);
    EXPECT_EQ(a.emissive, m.emissive);
}

TEST(Srgb, RoundTripsEveryByte) {
    for (int i = 0; i < 256; ++i)
        EXPECT_EQ(std::lround(linear_to_srgb(srgb_to_linear(i / 255.0f)) * 255.0f), i);
}

TEST(Camera, CentreRayLooksForwardAndCornersSpanTheFieldOfView) {
    Camera cam;
    cam.yfov = glm::radians(90.0f);
    const Ray<float> centre = camera_ray<float>(cam, 200, 100, 100.0f, 50.0f);
    EXPECT_NEAR(centre.direction.z, -1.0f, 1e-6f);
    // Top edge at 45 degrees up; left edge at atan(aspect * tan(45)) = atan(2).
    const Ray<float> top = camera_ray<float>(cam, 200, 100, 100.0f, 0.0f);
    EXPECT_NEAR(top.direction.y, -top.direction.z, 1e-6f);
    const Ray<float> left = camera_ray<float>(cam, 200, 100, 0.0f, 50.0f);
    EXPECT_NEAR(left.direction.x / left.direction.z, 2.0f, 1e-5f);
}

TEST(Camera, OrthographicRaysAreParallel) {
    Camera cam;
    cam.projection = Projection::Orthographic;
    cam.xmag = 2.0f;
    cam.ymag = 1.0f;
    const Ray<float> a = camera_ray<float>(cam, 10, 10, 0.0f, 0.0f);
    const Ray<float> b = camera_ray<float>(cam, 10, 10, 10.0f, 10.0f);
    EXPECT_EQ(a.direction, b.direction);
    EXPECT_NEAR(a.origin.x, -2.0f, 1e-6f);
    EXPECT_NEAR(b.origin.y, -1.0f, 1e-6f);
}

}  // namespace
}  // namespace rt
