// Scenes for the alpha cut-out tests (common/trace/opacity_test.cpp, 01_naive/brute_force_cutouts_test.cpp): one
// triangle and a MASK material.
#pragma once

#include "common/scene/scene.h"

namespace rt {

// One triangle (0,0,0) (1,0,0) (0,1,0) with uvs equal to its xy, and one material.
inline Scene one_triangle(const Material& m) {
    Scene s;
    s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    s.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    s.uvs = {{0, 0}, {1, 0}, {0, 1}};
    s.material_ids = {0};
    s.materials = {m};
    return s;
}

// A MASK material: base colour alpha `factor_alpha`, cut off below `cutoff`.
inline Material masked(float factor_alpha, float cutoff) {
    Material m;
    m.base_color.a = factor_alpha;
    m.alpha_mode = AlphaMode::Mask;
    m.alpha_cutoff = cutoff;
    return m;
}

}  // namespace rt
