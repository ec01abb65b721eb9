// Absorption inside transmitting volumes (KHR_materials_volume; docs/shading.md, "Absorption"). The GLSL twin is
// common/shaders/trace/absorption.glsl.
//
// Beer-Lambert: light that travels a distance t through a medium with absorption coefficient sigma_a keeps the
// fraction exp(-sigma_a t) per channel. glTF gives the medium as the colour c that white light takes after the
// distance d, so c = exp(-sigma_a d), sigma_a = -ln(c) / d, and the transmittance is c^(t / d).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/scene/effects.h"
#include "common/scene/scene.h"

namespace rt {

// sigma_a per channel, 0 for a material that does not absorb (thin-walled, not transmitting, infinite distance).
// Finite and >= 0 for every material: a channel with c = 0 (everything absorbed) or a tiny d gets the largest float,
// so exp(-sigma_a t) is 0 for any t > 0 and 1 for t = 0, never NaN.
inline glm::vec3 absorption_coefficient(const Material& m) {
    if (!material_absorbs(m) || !(m.attenuation_distance > 0.0f)) return glm::vec3(0.0f);
    glm::vec3 sigma;
    for (int i = 0; i < 3; ++i) {
        const float c = std::clamp(m.attenuation_color[i], 0.0f, 1.0f);
        const float s = -std::log(c) / m.attenuation_distance;   // +inf for c = 0; -0 for c = 1
        sigma[i] = std::min(std::max(s, 0.0f), std::numeric_limits<float>::max());
    }
    return sigma;
}

// exp(-sigma_a t): the fraction of the radiance that survives a segment of length t >= 0 inside the medium.
inline glm::vec3 transmittance(const glm::vec3& sigma, float t) {
    return {std::exp(-(sigma.x * t)), std::exp(-(sigma.y * t)), std::exp(-(sigma.z * t))};
}

}  // namespace rt
