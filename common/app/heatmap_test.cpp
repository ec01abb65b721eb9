// --heatmap: counts map onto the colour scale between the frame's min and max, and the colour bar states the scale.
#include <gtest/gtest.h>

#include "heatmap.h"

namespace rt {
namespace {

float brightness(const glm::vec3& c) { return c.r + c.g + c.b; }

TEST(Heatmap, MinAndMaxTakeTheEndsOfTheColourScale) {
    const std::vector<std::uint32_t> tests = {10, 20, 30, 40, 50, 60};   // 3x2
    const Heatmap h = make_heatmap(tests, 3, 2, HeatmapScale::Linear);
    EXPECT_EQ(h.min, 10u);
    EXPECT_EQ(h.max, 60u);
    EXPECT_EQ(h.total, 210u);
    EXPECT_EQ(h.image.width, 3);
    EXPECT_EQ(h.image.height, 2 + h.colour_bar_rows);
    EXPECT_EQ(h.image.at(0, 0), heatmap_colour(0.0f));
    EXPECT_EQ(h.image.at(2, 1), heatmap_colour(1.0f));
    EXPECT_EQ(h.image.at(0, 1), heatmap_colour(0.6f));   // 40 of 10..60
    // More tests, a brighter colour.
    for (float s = 0.0f; s < 1.0f; s += 0.05f) EXPECT_LT(brightness(heatmap_colour(s)), brightness(heatmap_colour(s + 0.05f)));
    const nlohmann::json j = heatmap_json(h);
    EXPECT_EQ(j["min"], 10);
    EXPECT_EQ(j["max"], 60);
    EXPECT_EQ(j["total"], 210);
    EXPECT_EQ(j["scale"], "linear");
    EXPECT_EQ(j["ticks"], nlohmann::json({10.0, 22.5, 35.0, 47.5, 60.0}));
}

// --heatmap-max: a fixed scale [0, max], so two heatmaps compare colour for colour; larger counts take the top.
TEST(Heatmap, AFixedMaxSpansZeroToItAndClampsLargerCounts) {
    const std::vector<std::uint32_t> tests = {10, 20, 30, 40, 50, 60};
    const Heatmap h = make_heatmap(tests, 3, 2, HeatmapScale::Linear, 40);
    EXPECT_EQ(h.min, 0u);
    EXPECT_EQ(h.max, 40u);
    EXPECT_EQ(h.image.at(0, 0), heatmap_colour(0.25f));   // 10 of 0..40
    EXPECT_EQ(h.image.at(0, 1), heatmap_colour(1.0f));    // 40
    EXPECT_EQ(h.image.at(2, 1), heatmap_colour(1.0f));    // 60, clamped
    EXPECT_EQ(heatmap_json(h)["ticks"], nlohmann::json({0.0, 10.0, 20.0, 30.0, 40.0}));
}

TEST(Heatmap, TheColourBarRunsFromMinToMaxWithTicks) {
    const Heatmap h = make_heatmap(std::vector<std::uint32_t>(101 * 40, 7), 101, 40, HeatmapScale::Linear);
    const int bottom = h.image.height - 1;   // below the ticks
    EXPECT_EQ(h.image.at(0, bottom), heatmap_colour(0.0f));
    EXPECT_EQ(h.image.at(50, bottom), heatmap_colour(0.5f));
    EXPECT_EQ(h.image.at(100, bottom), heatmap_colour(1.0f));
    EXPECT_EQ(h.image.at(25, 40), glm::vec3(1.0f));   // tick at 1/4: white on the dark half
    EXPECT_EQ(h.image.at(75, 40), glm::vec3(0.0f));   // tick at 3/4: black on the bright half
    EXPECT_EQ(h.image.at(0, 0), heatmap_colour(0.0f));   // all counts equal: the bottom of the scale, no NaN
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
