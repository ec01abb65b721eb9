// --heatmap: counts map onto a colour scale from 0 to the frame's most tests (or --heatmap-max), and the colour bar
// states the scale with numbers under its ticks.
#include <gtest/gtest.h>

#include "heatmap.h"

namespace rt {
namespace {

float brightness(const glm::vec3& c) { return c.r + c.g + c.b; }

TEST(Heatmap, TheScaleRunsFromZeroToTheFramesMostTests) {
    const std::vector<std::uint32_t> tests = {10, 20, 30, 40, 50, 60};   // 3x2
    const Heatmap h = make_heatmap(tests, 3, 2, HeatmapScale::Linear);
    EXPECT_EQ(h.min, 10u);
    EXPECT_EQ(h.max, 60u);
    EXPECT_EQ(h.scale_max, 60u);
    EXPECT_EQ(h.total, 210u);
    EXPECT_EQ(h.image.width, 3);
    EXPECT_EQ(h.image.height, 2 + h.colour_bar_rows);
    EXPECT_EQ(h.image.at(0, 0), heatmap_colour(10.0f / 60.0f)) << "the fewest tests are not the bottom: 0 is";
    EXPECT_EQ(h.image.at(2, 1), heatmap_colour(1.0f));
    EXPECT_EQ(h.image.at(0, 1), heatmap_colour(40.0f / 60.0f));
    // More tests, a brighter colour.
    for (float s = 0.0f; s < 1.0f; s += 0.05f) EXPECT_LT(brightness(heatmap_colour(s)), brightness(heatmap_colour(s + 0.05f)));
    const nlohmann::json j = heatmap_json(h);
    EXPECT_EQ(j["min"], 10);
    EXPECT_EQ(j["max"], 60);
    EXPECT_EQ(j["scale_max"], 60);
    EXPECT_EQ(j["total"], 210);
    EXPECT_EQ(j["scale"], "linear");
    EXPECT_EQ(j["ticks"], nlohmann::json({0.0, 15.0, 30.0, 45.0, 60.0}));
}

// A frame where every pixel cost the same reads as that cost (the top of its scale), not as "no tests".
TEST(Heatmap, AUniformCostIsTheTopColourAndNoTestsTheBottom) {
    const Heatmap uniform = make_heatmap(std::vector<std::uint32_t>(12, 7), 4, 3, HeatmapScale::Linear);
    EXPECT_EQ(uniform.image.at(1, 1), heatmap_colour(1.0f));
    const Heatmap none = make_heatmap(std::vector<std::uint32_t>(12, 0), 4, 3, HeatmapScale::Linear);
    EXPECT_EQ(none.image.at(1, 1), heatmap_colour(0.0f)) << "no test at all: the bottom, no NaN";
    EXPECT_LT(brightness(none.image.at(1, 1)), brightness(uniform.image.at(1, 1)));
}

// --heatmap-max: a fixed scale [0, max], so two heatmaps compare colour for colour; larger counts take the top.
TEST(Heatmap, AFixedMaxSpansZeroToItAndClampsLargerCounts) {
    const std::vector<std::uint32_t> tests = {10, 20, 30, 40, 50, 60};
    const Heatmap h = make_heatmap(tests, 3, 2, HeatmapScale::Linear, 40);
    EXPECT_EQ(h.min, 10u);
    EXPECT_EQ(h.max, 60u);
    EXPECT_EQ(h.scale_max, 40u);
    EXPECT_EQ(h.image.at(0, 0), heatmap_colour(0.25f));   // 10 of 0..40
    EXPECT_EQ(h.image.at(0, 1), heatmap_colour(1.0f));    // 40
    EXPECT_EQ(h.image.at(2, 1), heatmap_colour(1.0f));    // 60, clamped
    EXPECT_EQ(heatmap_json(h)["ticks"], nlohmann::json({0.0, 10.0, 20.0, 30.0, 40.0}));
}

TEST(Heatmap, TheColourBarRunsFromZeroToTheTopWithTicksAndNumbers) {
    const Heatmap h = make_heatmap(std::vector<std::uint32_t>(101 * 40, 7), 101, 40, HeatmapScale::Linear);
    const int bar_bottom = h.image.height - h.label_rows - 1;   // the bar's last row, below the tick marks
    EXPECT_EQ(h.image.at(0, bar_bottom), heatmap_colour(0.0f));
    EXPECT_EQ(h.image.at(50, bar_bottom), heatmap_colour(0.5f));
    EXPECT_EQ(h.image.at(100, bar_bottom), heatmap_colour(1.0f));
    EXPECT_EQ(h.image.at(25, 40), glm::vec3(1.0f));   // tick at 1/4: white on the dark half
    EXPECT_EQ(h.image.at(75, 40), glm::vec3(0.0f));   // tick at 3/4: black on the bright half
    // The numbers: a band of light text on black under the bar, some of it under each tick's place.
    ASSERT_GT(h.label_rows, 0) << "no font for the tick numbers (scripts/setup installs fonts-dejavu-core)";
    const int top = h.image.height - h.label_rows;
    for (int tick = 0; tick < 5; ++tick) {
        const int centre = tick * 25, from = std::max(0, centre - 12), to = std::min(100, centre + 12);
        bool ink = false;
        for (int y = top; y < h.image.height; ++y)
            for (int x = from; x <= to; ++x) ink = ink || brightness(h.image.at(x, y)) > 1.5f;
        EXPECT_TRUE(ink) << "no number near tick " << tick;
    }
}

TEST(Heatmap, TickLabelsAreShortNumbers) {
    EXPECT_EQ(heatmap_tick_label(0.0), "0");
    EXPECT_EQ(heatmap_tick_label(17.5), "18");
    EXPECT_EQ(heatmap_tick_label(950.0), "950");
    EXPECT_EQ(heatmap_tick_label(1500.0), "1.5k");
    EXPECT_EQ(heatmap_tick_label(12500.0), "12.5k");
    EXPECT_EQ(heatmap_tick_label(3.2e6), "3.2M");
    EXPECT_EQ(heatmap_tick_label(4.25e7), "42.5M");
}

TEST(Heatmap, LogScaleSpreadsSmallCounts) {
    const std::vector<std::uint32_t> tests = {0, 9, 99};
    const Heatmap h = make_heatmap(tests, 3, 1, HeatmapScale::Log);
    EXPECT_EQ(h.image.at(1, 0), heatmap_colour(0.5f));   // log(1 + 9) / log(1 + 99)
    EXPECT_NEAR(h.ticks[2], 9.0, 1e-9);
    EXPECT_EQ(heatmap_json(h)["scale"], "log");
}

TEST(Heatmap, ACountPerPixelIsRequired) {
    EXPECT_THROW(make_heatmap({}, 4, 4, HeatmapScale::Linear), std::runtime_error);
}

}  // namespace
}  // namespace rt
