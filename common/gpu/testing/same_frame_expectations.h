// For the unit tests of the GPU stages: two frames that must be the same frame, as the exact cross-stage checks
// demand (tests/README.md): the image bit for bit, the ray counts of every kind, and every hit record's pixel, path,
// kind, triangle and t (bits) in the same order. Only tests include it (it needs GoogleTest).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "common/app/renderer.h"

namespace rt {

inline std::uint32_t float_bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

inline void expect_same_frame(const FrameResult& a, const FrameResult& b, const std::string& what) {
    ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size()) << what;
    for (std::size_t i = 0; i < a.image.pixels.size(); ++i) ASSERT_EQ(a.image.pixels[i], b.image.pixels[i]) << what;
    for (int k = 0; k < 4; ++k) ASSERT_EQ(a.stats.counters.rays[k], b.stats.counters.rays[k]) << what;
    ASSERT_EQ(a.hits.size(), b.hits.size()) << what;
    for (std::size_t i = 0; i < a.hits.size(); ++i) {
        ASSERT_EQ(a.hits[i].pixel, b.hits[i].pixel) << what << " ray " << i;
        ASSERT_EQ(a.hits[i].path, b.hits[i].path) << what << " ray " << i;
        ASSERT_EQ(a.hits[i].kind_light, b.hits[i].kind_light) << what << " ray " << i;
        ASSERT_EQ(a.hits[i].triangle, b.hits[i].triangle) << what << " ray " << i;
        ASSERT_EQ(float_bits(a.hits[i].t), float_bits(b.hits[i].t)) << what << " ray " << i;
    }
}

}  // namespace rt
