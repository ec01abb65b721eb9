// --heatmap FILE: a false-colour picture of the ray/triangle tests spent on each pixel (all rays of the pixel's tree,
// FrameResult::tests_per_pixel): what an acceleration structure buys, stage by stage.
//
// Dark purple is the frame's fewest tests, pale yellow its most (the "inferno" colour map: brightness grows with the
// count, and it reads in grey too). Below the picture a colour bar spans min..max left to right, with tick marks at
// 0, 1/4, 1/2, 3/4 and 1 of the scale; the stats JSON states min, max, the scale and the tick values.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "image.h"

namespace rt {

enum class HeatmapScale { Linear, Log };   // log: log(1 + count - min), for counts spanning orders of magnitude

struct Heatmap {
    Image image;                // the picture (width x height), then colour_bar_rows rows of colour bar
    int colour_bar_rows = 0;
    std::uint32_t min = 0, max = 0;
    std::uint64_t total = 0;    // the sum over the pixels: the frame's intersection_tests (every test has a pixel)
    HeatmapScale scale = HeatmapScale::Linear;
    std::vector<double> ticks;  // the counts at the tick marks, left to right
};

// tests_per_pixel has width * height entries (y * width + x).
// fixed_max > 0 (--heatmap-max): the scale runs from 0 to fixed_max whatever the image holds (larger counts take the
// top colour), so heatmaps of two stages or settings can be compared colour for colour.
Heatmap make_heatmap(const std::vector<std::uint32_t>& tests_per_pixel, int width, int height, HeatmapScale scale,
                     std::uint32_t fixed_max = 0);

// {"min", "max", "total", "scale", "ticks", "colour_bar_rows"} for the stats JSON.
nlohmann::json heatmap_json(const Heatmap& heatmap);

// The colour of s in [0, 1] (linear RGB, written as the sRGB of the colour map).
glm::vec3 heatmap_colour(float s);

}  // namespace rt
