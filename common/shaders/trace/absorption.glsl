// Absorption inside transmitting volumes: the GLSL twin of common/trace/absorption.h (docs/shading.md,
// "Absorption"). sigma_a comes precomputed per material (Material.attenuation = rt::absorption_coefficient), so only
// the exponential is computed here: GLSL's exp is not IEEE-exact, the twins test bounds its relative error.
#include "scene.glsl"

// exp(-sigma_a t): the fraction of the radiance that survives a segment of length t inside the medium.
vec3 transmittance(vec3 sigma, float t) {
    precise vec3 x = -(sigma * t);
    return exp(x);
}
