#include "heatmap.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <stdexcept>

#ifndef RT_PORTABLE
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#endif

#include "common/trace/shading.h"

namespace rt {

namespace {

constexpr float kTickPositions[] = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};

// Position of `count` on the scale 0..top, in [0, 1].
float position(std::uint32_t count, std::uint32_t top, HeatmapScale scale) {
    if (top == 0) return 0.0f;
    const double v = double(std::min(count, top)), range = double(top);
    return float(scale == HeatmapScale::Log ? std::log1p(v) / std::log1p(range) : v / range);
}

// The count at position s: the inverse of position().
double count_at(float s, std::uint32_t top, HeatmapScale scale) {
    const double range = double(top);
    return scale == HeatmapScale::Log ? std::expm1(double(s) * std::log1p(range)) : double(s) * range;
}

// The tick numbers under the colour bar, white on the image's dark label band, through OpenImageIO's text
// rendering (FreeType with the DejaVu font scripts/setup installs). Returns false when no font could be loaded.
bool draw_tick_labels(Image& image, int top_row, int rows, const std::vector<double>& ticks) {
#ifdef RT_PORTABLE
    (void)image, (void)top_row, (void)rows, (void)ticks;
    return false;
#else
    namespace OIIO = OIIO_NAMESPACE;
    OIIO::ImageBuf band(OIIO::ImageSpec(image.width, rows, 3, OIIO::TypeDesc::FLOAT));
    OIIO::ImageBufAlgo::zero(band);
    const int size = std::max(8, rows - 2);
    const float white[] = {1.0f, 1.0f, 1.0f};
    for (std::size_t i = 0; i < ticks.size(); ++i) {
        const float s = ticks.size() > 1 ? float(i) / float(ticks.size() - 1) : 0.0f;
        const int x = int(std::lround(s * float(image.width - 1)));
        const auto align = i == 0 ? OIIO::ImageBufAlgo::TextAlignX::Left
                           : i + 1 == ticks.size() ? OIIO::ImageBufAlgo::TextAlignX::Right
                                                   : OIIO::ImageBufAlgo::TextAlignX::Center;
        if (!OIIO::ImageBufAlgo::render_text(band, x, rows - 2, heatmap_tick_label(ticks[i]), size, "DejaVuSans",
                                             white, align))
            return false;
    }
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < image.width; ++x) {
            float c[3];
            band.getpixel(x, y, c, 3);
            image.at(x, top_row + y) = glm::vec3(c[0], c[1], c[2]);
        }
    return true;
#endif
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

std::string heatmap_tick_label(double count) {
    char text[32];
    const double a = std::abs(count);
    if (a < 1e3)
        std::snprintf(text, sizeof text, "%.0f", count);
    else if (a < 1e6)
        std::snprintf(text, sizeof text, a < 1e4 ? "%.2gk" : "%.3gk", count / 1e3);
    else
        std::snprintf(text, sizeof text, a < 1e7 ? "%.2gM" : "%.3gM", count / 1e6);
    return text;
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
    h.scale_max = fixed_max > 0 ? fixed_max : h.max;
    h.total = std::accumulate(tests.begin(), tests.end(), std::uint64_t(0));
    const int bar_rows = std::max(4, height / 10);
    h.label_rows = std::clamp(width / 16, 10, 24);
    h.colour_bar_rows = bar_rows + h.label_rows;
    h.image = Image(width, height + h.colour_bar_rows);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            h.image.at(x, y) = heatmap_colour(position(tests[std::size_t(y) * std::size_t(width) + std::size_t(x)],
                                                       h.scale_max, scale));   // > scale_max: the top colour
    // The colour bar: left edge = 0, right edge = scale_max; its top third carries the ticks (white on the dark
    // half, black on the bright half); the numbers go below it.
    const int tick_rows = (bar_rows + 2) / 3;
    for (int x = 0; x < width; ++x) {
        const float s = width > 1 ? float(x) / float(width - 1) : 0.0f;
        for (int y = height; y < height + bar_rows; ++y) h.image.at(x, y) = heatmap_colour(s);
    }
    for (float s : kTickPositions) {
        const int x = int(std::lround(s * float(width - 1)));
        for (int y = height; y < height + tick_rows; ++y) h.image.at(x, y) = glm::vec3(s < 0.5f ? 1.0f : 0.0f);
        h.ticks.push_back(count_at(s, h.scale_max, scale));
    }
    if (!draw_tick_labels(h.image, height + bar_rows, h.label_rows, h.ticks)) {
        h.colour_bar_rows = bar_rows;   // no font: no label band
        h.label_rows = 0;
        h.image.pixels.resize(std::size_t(width) * std::size_t(height + bar_rows));
        h.image.height = height + bar_rows;
    }
    return h;
}

nlohmann::json heatmap_json(const Heatmap& h) {
    return {{"min", h.min},
            {"max", h.max},
            {"scale_max", h.scale_max},
            {"total", h.total},
            {"scale", h.scale == HeatmapScale::Log ? "log" : "linear"},
            {"ticks", h.ticks},
            {"colour_bar_rows", h.colour_bar_rows},
            {"label_rows", h.label_rows}};
}

}  // namespace rt
