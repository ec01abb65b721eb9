// Where inside a pixel the samples of --spp N fall: the same pattern for every stage, so their images agree.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

namespace rt {

// One sample: the pixel centre. N samples: the first N points of the R2 low-discrepancy sequence (Roberts 2018,
// based on the plastic number), which fills the pixel evenly for any N, unlike a square grid.
inline std::vector<glm::vec2> pixel_sample_offsets(int spp) {
    std::vector<glm::vec2> offsets;
    if (spp <= 1) return {glm::vec2(0.5f)};
    const double g = 1.32471795724474602596;   // plastic number: g^3 = g + 1
    const double a1 = 1.0 / g, a2 = 1.0 / (g * g);
    for (int i = 0; i < spp; ++i) {
        const double x = 0.5 + a1 * (i + 1), y = 0.5 + a2 * (i + 1);
        offsets.emplace_back(float(x - std::floor(x)), float(y - std::floor(y)));
    }
    return offsets;
}

}  // namespace rt
