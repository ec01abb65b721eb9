#include "heatmap.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "../trace/shading.h"

namespace rt {

namespace {

constexpr float kTickPositions[] = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};

// Position of `count` on the scale, in [0, 1].
float position(std::uint32_t count, std::uint32_t min, std::uint32_t max, HeatmapScale scale) {
    if (max <= min) return 0.0f;
    const double v = double(count - min), range = double(max - min);
    return float(scale == HeatmapScale::Log ? std::log1p(v) / std::log1p(range) : v / range);
}

// The count at position s: the inverse of position().
double count_at(float s, std::uint32_t min, std::uint32_t max, HeatmapScale scale) {
    const double range = double(max - min);
    return double(min) + (scale == HeatmapScale::Log ? std::expm1(double(s) * std::log1p(range)) : double(s) * range);
}

}  // namespace

glm::vec3 heatmap_colour(float s) {
    // Five stops of matplotlib's "inferno", in sRGB 0-255, interpolated in sRGB.
    static const glm::vec3 stops[] = {{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
    const float x = std::clamp(s, 0.0f, 1.0f) * 4.0f;
    const int i = std::min(int(x), 3);
    const glm::vec3 srgb = glm::mix(stops[i], stops[i + 1], x - float(i)) / 255.0f;
    return {srgb_to_linear(srgb.r), srgb_to_linear(srgb.g), srgb_to_linear(srgb.b)};
}

Heatmap make_heatmap(const std::vector<std::uint32_t>& tests, int width, int height, HeatmapScale scale,
                     std::uint32_t fixed_max) {
    if (tests.size() != std::size_t(width) * std::size_t(height))
        throw std::runtime_error("--heatmap: the stage counted tests for " + std::to_string(tests.size()) +
                                 " pixels, not " + std::to_string(width) + "x" + std::to_string(height));
    Heatmap h;
    h.scale = scale;
    h.min = tests.empty() ? 0 : *std::min_element(tests.begin(), tests.end());
    h.max = tests.empty() ? 0 : *std::max_element(tests.begin(), tests.end());
    if (fixed_max > 0) {
        h.min = 0;
        h.max = fixed_max;
    }
    h.total = std::accumulate(tests.begin(), tests.end(), std::uint64_t(0));
    h.colour_bar_rows = std::max(4, height / 10);
    h.image = Image(width, height + h.colour_bar_rows);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            h.image.at(x, y) = heatmap_colour(position(tests[std::size_t(y) * std::size_t(width) + std::size_t(x)],
                                                       h.min, h.max, scale));   // > max: clamped to the top
    // The colour bar: left edge = min, right edge = max; its top third carries the ticks (white on the dark half,
    // black on the bright half).
    const int tick_rows = (h.colour_bar_rows + 2) / 3;
    for (int x = 0; x < width; ++x) {
        const float s = width > 1 ? float(x) / float(width - 1) : 0.0f;
        for (int y = height; y < height + h.colour_bar_rows; ++y) h.image.at(x, y) = heatmap_colour(s);
    }
    for (float s : kTickPositions) {
        const int x = int(std::lround(s * float(width - 1)));
        for (int y = height; y < height + tick_rows; ++y) h.image.at(x, y) = glm::vec3(s < 0.5f ? 1.0f : 0.0f);
        h.ticks.push_back(count_at(s, h.min, h.max, scale));
    }
    return h;
}

nlohmann::json heatmap_json(const Heatmap& h) {
    return {{"min", h.min},
            {"max", h.max},
            {"total", h.total},
            {"scale", h.scale == HeatmapScale::Log ? "log" : "linear"},
            {"ticks", h.ticks},
            {"colour_bar_rows", h.colour_bar_rows}};
}

}  // namespace rt
