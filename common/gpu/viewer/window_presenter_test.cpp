#include "window_presenter.h"

#include <bit>
#include <cstdint>

#include <gtest/gtest.h>

namespace rt::gpu {
namespace {

// What the display pass (common/shaders/viewer/display.comp, encode) computes from the table.
int encode_with(const std::array<float, 256>& threshold, float v) {
    int k = 0;
    for (int step = 128; step > 0; step >>= 1)
        if (k + step <= 255 && threshold[std::size_t(k + step)] <= v) k += step;
    return k;
}

TEST(WindowPresenter, Srgb8ThresholdsEncodeEveryValueAsThePngWriterDoes) {
    const std::array<float, 256> threshold = srgb8_thresholds();
    Image image(1, 1);
    auto png_byte = [&](float v) {
        image.pixels[0] = glm::vec3(v);
        return int(to_srgb8(image)[0]);
    };
    // Every threshold and its neighbouring floats, then a sweep of [-0.1, 1.1] in small steps.
    for (std::size_t k = 1; k < 256; ++k) {
        const std::uint32_t bits = std::bit_cast<std::uint32_t>(threshold[k]);
        for (std::uint32_t b : {bits - 1, bits, bits + 1}) {
            const float v = std::bit_cast<float>(b);
            EXPECT_EQ(encode_with(threshold, v), png_byte(v)) << v;
        }
    }
    for (float v = -0.1f; v < 1.1f; v += 1.0f / 4099.0f) EXPECT_EQ(encode_with(threshold, v), png_byte(v)) << v;
    EXPECT_EQ(encode_with(threshold, 1e30f), 255);
}

}  // namespace
}  // namespace rt::gpu
