// What a ray that leaves the scene brings back (docs/shading.md, "The environment"): the environment map's radiance
// in its direction when the scene has one, else the background colour. GLSL twin:
// common/shaders/trace/environment.glsl, written operation for operation alike (environment_glsl_test.cpp checks they
// agree to the bit).
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "common/scene/environment_map.h"
#include "common/scene/scene.h"

namespace rt {

// atan2(y, x) in [-pi, pi] by a degree-9 polynomial (Abramowitz & Stegun 4.4.47: |error| < 1.2e-5 rad in float)
// made of +, -, *, / only, so the GLSL twin rounds exactly like it (GLSL's own atan has no stated precision).
// 1.2e-5 rad is 0.03 texel on a 16384-wide map.
float environment_atan2(float y, float x);

// The map coordinates of a world direction (not necessarily unit length), with the rotation (cos, sin) of
// Environment::rotation: the direction is turned by -angle about +Y, then
//     u = 0.5 + atan2(x, -z) / (2 pi)     -Z (glTF's default view direction) is the image's centre, u = 0.5; u grows
//                                         towards +X, so the image is seen unmirrored from inside; the seam is at +Z
//     v = atan2(sqrt(x^2 + z^2), y) / pi  v = 0 straight up (+Y, the top row), 1 straight down.
glm::vec2 environment_uv(const glm::vec3& direction, const glm::vec2& rotation);

// Bilinear between the four texel centres around (u, v), wrapping in u (the seam is continuous), clamping in v.
glm::vec3 sample_environment(const Environment& environment, const glm::vec2& uv);

// The default world (docs/shading.md, "Defaults"): what rays leaving a glTF file see when it says nothing of it and
// no --background or --environment is given. A neutral grey studio, brighter above than below: radiance
// kWorldNadir + (kWorldZenith - kWorldNadir) * (1 + y) / 2 for a unit direction of height y (0.6 at the horizon), the
// same in every direction around +Y. It is an environment map (8 x 64 texels, rows sampled at their centres and
// interpolated bilinearly like any map), so the C++ and GLSL lookups that agree to the bit already serve it.
constexpr float kWorldZenith = 0.9f, kWorldNadir = 0.3f;
std::shared_ptr<const Environment> default_world();

// The radiance a ray leaving the scene in `direction` brings back: the environment's, or the background colour.
glm::vec3 miss_radiance(const Scene& scene, const glm::vec3& direction);

}  // namespace rt
