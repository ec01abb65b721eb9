#include "exposure.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include <gtest/gtest.h>

namespace rt {
namespace {

Image ramp() {
    Image image(4, 2);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = glm::vec3(0.013f * float(i), 0.37f + float(i), 1e-6f * float(i + 1));
    return image;
}

TEST(Exposure, EvOneDoublesLinearValuesExactly) {
    const Image in = ramp();
    const Image out = apply_exposure(in, parse_exposure("1"));
    for (std::size_t i = 0; i < in.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(out.pixels[i][c], 2.0f * in.pixels[i][c]);
}

TEST(Exposure, EvMinusTwoQuartersLinearValuesExactly) {
    const Image in = ramp();
    const Image out = apply_exposure(in, parse_exposure("-2"));
    for (std::size_t i = 0; i < in.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(out.pixels[i][c], 0.25f * in.pixels[i][c]);
}

TEST(Exposure, ZeroWithoutToneCurveLeavesTheImageBitForBit) {
    const Image in = ramp();
    const Image out = apply_exposure(in, Exposure{});
    EXPECT_EQ(0, std::memcmp(in.pixels.data(), out.pixels.data(), in.pixels.size() * sizeof(glm::vec3)));
}

TEST(Exposure, RefusesNonFiniteOutOfRangeAndWords) {
    for (const char* bad : {"nan", "inf", "-inf", "21", "-20.5", "1e9", "", "bright", "1x"})
        EXPECT_THROW(parse_exposure(bad), std::invalid_argument) << bad;
    EXPECT_EQ(parse_exposure("20").ev, 20.0f);
    EXPECT_EQ(parse_exposure("-20").ev, -20.0f);
    EXPECT_TRUE(parse_exposure("auto").automatic);
}

TEST(Exposure, AutoMapsThe99thPercentileLuminanceToOne) {
    Image image(100, 1);
    for (int i = 0; i < 100; ++i) image.pixels[std::size_t(i)] = glm::vec3(float(i + 1) * 0.5f);   // grey 0.5 .. 50
    // Luminance of a grey is its value; the 99th of 100 sorted values is 99 * 0.5.
    EXPECT_FLOAT_EQ(auto_exposure_ev(image), -std::log2(49.5f));
    const Image out = apply_exposure(image, parse_exposure("auto"));
    EXPECT_FLOAT_EQ(out.pixels[98].g, 1.0f);
    EXPECT_EQ(auto_exposure_ev(Image(3, 3)), 0.0f);   // black: nothing to expose for
}

TEST(Exposure, HugeValuesStayFinite) {
    Image image(1, 1);
    image.pixels[0] = glm::vec3(3e38f);
    const Image out = apply_exposure(image, parse_exposure("20"));
    EXPECT_TRUE(std::isfinite(out.pixels[0].r));
}

TEST(Exposure, AcesCurveIsMonotoneAndBoundedByOne) {
    EXPECT_EQ(aces_curve(0.0f), 0.0f);
    float previous = 0.0f;
    for (float x = 0.01f; x < 1000.0f; x *= 1.5f) {
        const float y = aces_curve(x);
        EXPECT_GE(y, previous);
        EXPECT_LE(y, 1.0f);
        previous = y;
    }
    EXPECT_GT(aces_curve(1000.0f), 0.99f);
}

}  // namespace
}  // namespace rt
