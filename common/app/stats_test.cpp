// The shared stats: rasterized primary rays are counted but not traced, the ray rate counts traced rays only, and
// every time phase reaches the JSON.
#include <gtest/gtest.h>

#include "stats.h"

namespace rt {
namespace {

FrameStats hybrid_frame() {   // a frame as stage 02 reports it: primary rays rasterized, secondary rays traced
    FrameStats s;
    s.counters.rays[int(RayKind::Primary)] = 1000;
    s.counters.rays[int(RayKind::Shadow)] = 300;
    s.counters.rays[int(RayKind::Reflection)] = 200;
    s.rasterized_rays = 1000;
    s.upload_ms = 1;
    s.raster_ms = 2;
    s.trace_ms = 0.5;
    s.shade_ms = 3;
    s.compile_ms = 40;
    s.total_ms = 50;
    return s;
}

TEST(Stats, MraysPerSecondCountsTracedRaysOnly) {
    const FrameStats s = hybrid_frame();
    EXPECT_EQ(s.traced_rays(), 500u);
    EXPECT_DOUBLE_EQ(s.mrays_per_s(), 500.0 / (0.5 * 1e3));   // 500 rays in 0.5 ms = 1 Mray/s
}

TEST(Stats, JsonSeparatesRasterizedFromTracedRaysAndSplitsTime) {
    const nlohmann::json j = make_stats_json("02_raster_hybrid", "whitted", 40, 25, "llvmpipe", {"shadows"},
                                             hybrid_frame());
    EXPECT_EQ(j["rays"]["primary"], 1000);
    EXPECT_EQ(j["rays"]["rasterized"], 1000);
    EXPECT_EQ(j["traced_rays"], 500);
    EXPECT_DOUBLE_EQ(j["mrays_per_s"].get<double>(), 1.0);
    const nlohmann::json& t = j["time_ms"];
    EXPECT_DOUBLE_EQ(t["upload"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(t["build"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(t["raster"].get<double>(), 2.0);
    EXPECT_DOUBLE_EQ(t["trace"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(t["shade"].get<double>(), 3.0);
    EXPECT_DOUBLE_EQ(t["compile"].get<double>(), 40.0);
    EXPECT_DOUBLE_EQ(t["total"].get<double>(), 50.0);
}

TEST(Stats, AddSumsCountsAndEveryPhase) {
    FrameStats run;
    run.add(hybrid_frame());
    run.add(hybrid_frame());
    EXPECT_EQ(run.counters.total_rays(), 3000u);
    EXPECT_EQ(run.rasterized_rays, 2000u);
    EXPECT_DOUBLE_EQ(run.upload_ms + run.raster_ms + run.trace_ms + run.shade_ms + run.compile_ms, 2 * 46.5);
    EXPECT_DOUBLE_EQ(run.total_ms, 100.0);
    EXPECT_DOUBLE_EQ(run.mrays_per_s(), 1.0);
}

}  // namespace
}  // namespace rt
