// --heatmap FILE: a false-colour picture of the ray/triangle tests spent on each pixel (all rays of the pixel's tree,
// FrameResult::tests_per_pixel): what an acceleration structure buys, stage by stage.
//
// The scale starts at 0 tests (near black) and ends at the frame's most tests, or at --heatmap-max (pale yellow):
// the "inferno" colour map, whose brightness grows with the count and reads in grey too. Starting at 0, not at the
// frame's fewest, keeps a frame of uniform cost from reading as "no tests", and makes two heatmaps with the same
// --heatmap-max comparable colour for colour. Below the picture a colour bar spans the scale left to right, with
// tick marks at 0, 1/4, 1/2, 3/4 and 1 and the count of each tick written under it; the stats JSON states min, max,
// the scale's top and the tick values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image.h"

namespace rt {

enum class HeatmapScale { Linear, Log };   // log: log(1 + count), for counts spanning orders of magnitude

struct Heatmap {
    Image image;                // the picture (width x height), then colour_bar_rows rows of colour bar and numbers
    int colour_bar_rows = 0;    // the bar itself and, below it, label_rows rows of tick numbers
    int label_rows = 0;         // 0 when no font could be loaded (the portable build): the numbers are in the JSON
    std::uint32_t min = 0, max = 0;   // the frame's fewest and most tests per pixel
    std::uint32_t scale_max = 0;      // the top of the scale: max, or --heatmap-max (the bottom is always 0)
    std::uint64_t total = 0;    // the sum over the pixels: the frame's intersection_tests (every test has a pixel)
    HeatmapScale scale = HeatmapScale::Linear;
    std::vector<double> ticks;  // the counts at the tick marks, left to right
};

// tests_per_pixel has width * height entries (y * width + x). The scale runs from 0 to the frame's most tests, or
// with fixed_max > 0 (--heatmap-max) to fixed_max whatever the image holds (larger counts take the top colour), so
// heatmaps of two stages or settings can be compared colour for colour.
Heatmap make_heatmap(const std::vector<std::uint32_t>& tests_per_pixel, int width, int height, HeatmapScale scale,
                     std::uint32_t fixed_max = 0);

// {"min", "max", "scale_max", "total", "scale", "ticks", "colour_bar_rows", "label_rows"} for the stats JSON.
nlohmann::json heatmap_json(const Heatmap& heatmap);

// The colour of s in [0, 1] (linear RGB, written as the sRGB of the colour map).
glm::vec3 heatmap_colour(float s);

// A tick's count as the colour bar writes it: "0", "950", "12.5k", "3.2M".
std::string heatmap_tick_label(double count);

}  // namespace rt
