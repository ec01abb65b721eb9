// The shared wavefront pipeline (common/gpu/pipeline/wavefront.h) as stage 02 runs it, with G-buffer primaries and
// the brute-force traversal:
//  - ordered queues: two runs give identical hit records (the queues' contents, in queue order), counts, per-pixel
//    tests and images, and primary hits come in 8x8 tiles, Morton order inside;
//  - the radiance sum holds photometric values (a 1e7 cd lamp, a 1e5 lux sun) and agrees with stage 01, saturates
//    instead of wrapping beyond its range, and many samples do not overflow;
//  - a batch traversal (Traversal::trace_batch) gives exactly what the per-ray traversal gives;
//  - a tiny storage-block limit (batches of tiles, of rays, of lights) gives exactly the same frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <tuple>

#include "01_naive/brute_force_tracer.h"
#include "common/app/pixel_samples.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "common/trace/whitted.h"
#include "02_raster_hybrid/gbuffer.h"
#include "common/gpu/pipeline/gpu_scene.h"
#include "common/gpu/testing/gpu_test_context.h"
#include "02_raster_hybrid/brute_force_traversal.h"
#include "common/gpu/pipeline/wavefront.h"
#include "tests/stage_test_fixture.h"

namespace rt {
namespace {

gpu::GlslTraversal kBruteForce("02_raster_hybrid/shaders/brute_force.glsl");   // per ray, one loop

// One frame as stage 02 renders it: G-buffer, then the pipeline, per sample.
FrameResult render_hybrid(const Scene& scene, const RenderSettings& settings, gpu::Traversal& traversal,
                          std::size_t max_storage_bytes = 0) {
    gpu::test_context();
    gpu::GpuScene gpu_scene;
    gpu_scene.upload(scene);
    gpu::GBuffer gbuffer;
    gpu::Wavefront wavefront(traversal);
    wavefront.max_storage_bytes = max_storage_bytes;
    wavefront.begin_frame(gpu_scene, settings);
    for (const glm::vec2& offset : pixel_sample_offsets(settings.spp)) {
        gbuffer.render(gpu_scene, scene.camera, scene.bounds, settings.width, settings.height, offset);
        gpu_scene.bind();
        gbuffer.shade_sample(wavefront, offset);
    }
    FrameResult result;
    wavefront.finish_frame(result);
    result.extra["pass_dispatches"] = wavefront.dispatches();
    return result;
}

bool same_bits(const Image& a, const Image& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)) == 0;
}

bool same_records(const std::vector<HitRecord>& a, const std::vector<HitRecord>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(HitRecord)) == 0;
}

std::vector<HitRecord> sorted_by_ray(std::vector<HitRecord> records) {
    std::sort(records.begin(), records.end(), [](const HitRecord& x, const HitRecord& y) {
        return std::tie(x.sample, x.pixel, x.path, x.kind_light) < std::tie(y.sample, y.pixel, y.path, y.kind_light);
    });
    return records;
}

void expect_same_frame(const FrameResult& a, const FrameResult& b, bool same_order) {
    EXPECT_TRUE(same_bits(a.image, b.image));
    for (int k = 0; k < 4; ++k) EXPECT_EQ(a.stats.counters.rays[k], b.stats.counters.rays[k]) << "ray kind " << k;
    EXPECT_EQ(a.stats.counters.intersection_tests, b.stats.counters.intersection_tests);
    EXPECT_EQ(a.tests_per_pixel, b.tests_per_pixel);
    if (same_order) {
        EXPECT_TRUE(same_records(a.hits, b.hits));
    } else {
        EXPECT_TRUE(same_records(sorted_by_ray(a.hits), sorted_by_ray(b.hits)));
    }
}

std::uint64_t traced_rays(const FrameResult& r) {
    const auto& c = r.stats.counters.rays;
    return c[int(RayKind::Primary)] + c[int(RayKind::Shadow)] + c[int(RayKind::Reflection)] +
           c[int(RayKind::Refraction)];
}

class OrderedQueues : public testing::TestWithParam<const char*> {};

TEST_P(OrderedQueues, TwoRunsGiveIdenticalQueuesCountsAndImages) {
    const Scene scene = builtin_scene_for(GetParam(), 64, 48);
    const RenderSettings settings = test_frame_settings(scene, 64, 48, true);
    const FrameResult first = render_hybrid(scene, settings, kBruteForce);
    const FrameResult second = render_hybrid(scene, settings, kBruteForce);
    expect_same_frame(first, second, true);
    // One record per ray, and the per-pixel tests add up to the total.
    EXPECT_EQ(first.hits.size(), traced_rays(first));
    std::uint64_t tests = 0;
    for (std::uint32_t t : first.tests_per_pixel) tests += t;
    EXPECT_EQ(tests, first.stats.counters.intersection_tests);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, OrderedQueues, testing::Values("whitted", "cornell", "spheres:16"),
                         [](const testing::TestParamInfo<const char*>& p) {
                             std::string name = p.param;
                             std::replace(name.begin(), name.end(), ':', '_');
                             return name;
                         });

// The queue order docs/gpu.md promises: primary hits tile by tile (8x8, row by row), Morton order inside; each
// later pass' rays grouped by kind (reflections before refractions) and shadow rays by light, each group in the
// order of the parents.
TEST(OrderedQueues, PrimaryHitsInTileMortonOrderSpawnedRaysGroupedByKind) {
    const int width = 20, height = 12;   // edge tiles only partly inside the image
    const Scene scene = builtin_scene_for("whitted", width, height);
    const FrameResult r = render_hybrid(scene, test_frame_settings(scene, width, height, true), kBruteForce);
    std::vector<std::uint32_t> expected;
    for (int ty = 0; ty < (height + 7) / 8; ++ty)
        for (int tx = 0; tx < (width + 7) / 8; ++tx)
            for (int m = 0; m < 64; ++m) {
                int x = 0, y = 0;
                for (int bit = 0; bit < 3; ++bit) {
                    x |= ((m >> (2 * bit)) & 1) << bit;
                    y |= ((m >> (2 * bit + 1)) & 1) << bit;
                }
                x += 8 * tx;
                y += 8 * ty;
                if (x < width && y < height) expected.push_back(std::uint32_t(y * width + x));
            }
    ASSERT_GE(r.hits.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(r.hits[i].pixel, expected[i]) << "primary " << i;
        EXPECT_EQ(ray_kind(r.hits[i].kind_light), RayKind::Primary);
    }
    // After the primaries: runs of one kind (and light); within a run of reflections or refractions of one depth,
    // parents (path / 2) keep the primary order, so pixels of depth-1 rays follow the primary order.
    std::vector<std::size_t> rank(std::size_t(width * height));
    for (std::size_t i = 0; i < expected.size(); ++i) rank[expected[i]] = i;
    int kind_changes = 0;
    for (std::size_t i = expected.size() + 1; i < r.hits.size(); ++i) {
        const HitRecord& a = r.hits[i - 1];
        const HitRecord& b = r.hits[i];
        if (a.kind_light != b.kind_light || a.path != b.path) {
            ++kind_changes;
            continue;
        }
        if (a.path <= 3) {
            EXPECT_LT(rank[a.pixel], rank[b.pixel]) << "record " << i;
        }
    }
    EXPECT_GT(kind_changes, 2);
}

// Records name rays in their tree (hit_record.h): a reflection (2p) or refraction (2p + 1) ray and a shadow ray
// (path p) each come from a hit of the ray with path p of the same pixel.
TEST(HitRecords, EveryRayHasTheParentHitItsPathNames) {
    const Scene scene = builtin_scene_for("whitted", 64, 48);
    const FrameResult r = render_hybrid(scene, test_frame_settings(scene, 64, 48, true), kBruteForce);
    std::set<std::pair<std::uint32_t, std::uint32_t>> hits;   // (pixel, path) of closest hits
    for (const HitRecord& h : r.hits)
        if (ray_kind(h.kind_light) != RayKind::Shadow && h.triangle >= 0)
            hits.insert({h.pixel, h.path});
    std::size_t checked = 0;
    for (const HitRecord& h : r.hits) {
        const auto kind = ray_kind(h.kind_light);
        if (kind == RayKind::Primary) {
            EXPECT_EQ(h.path, 1u);
            continue;
        }
        const bool shadow = kind == RayKind::Shadow;
        const std::uint32_t parent = shadow ? h.path : h.path / 2;
        if (shadow) {
            EXPECT_LT(light_index(h.kind_light), scene.lights.size());
        } else {
            EXPECT_EQ(h.path % 2, kind == RayKind::Refraction ? 1u : 0u);
        }
        EXPECT_TRUE(hits.count({h.pixel, parent})) << "pixel " << h.pixel << " path " << h.path;
        ++checked;
    }
    EXPECT_GT(checked, 1000u);
}

// The whitted scene (its mirror and glass add several terms per pixel) with one bright light instead of its own.
// Both lights below give pixels far beyond the 32767 where the old 32-bit sum clamped or wrapped.
Scene bright_scene(LightType type, float intensity, int width, int height) {
    Scene scene = builtin_scene_for("whitted", width, height);
    Light light;
    light.type = type;
    light.intensity = intensity;
    light.position = scene.bounds.lo + glm::vec3(0.5f, 0.9f, 0.5f) * (scene.bounds.hi - scene.bounds.lo);
    light.direction = glm::normalize(glm::vec3(0.1f, -1.0f, -0.1f));
    scene.lights = {light};
    return scene;
}

// Stage 01's radiance: the mean over the sample positions of --spp.
Image render_stage01(const Scene& scene, const RenderSettings& settings) {
    const BruteForceTracer<float> tracer(scene, settings.intersect);
    WhittedSettings ws;
    ws.effects = settings.effects;
    ws.max_depth = settings.max_depth;
    const Whitted<float, BruteForceTracer<float>> whitted(scene, tracer, ws);
    Image image(settings.width, settings.height);
    RayCounters counters;
    const std::vector<glm::vec2> offsets = pixel_sample_offsets(settings.spp);
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) {
            glm::vec3 sum(0.0f);
            for (const glm::vec2& o : offsets) {
                const Ray<float> ray =
                    camera_ray<float>(scene.camera, settings.width, settings.height, float(x) + o.x, float(y) + o.y);
                sum += whitted.radiance(ray, 0, glm::vec3(1.0f), counters);
            }
            image.pixels[std::size_t(y) * settings.width + x] = sum / float(offsets.size());
        }
    return image;
}

// Relative agreement with stage 01: |gpu - cpu| <= 1e-3 max(|cpu|, 1e-3) per channel (the GPU's pow differs by up
// to 1e-4; the fixed-point sum adds at most 2^-33 per term). Edge pixels where rasterization and the ray test pick
// different triangles may differ: at most 0.5% of the pixels (visibility_test.cpp's bound).
void expect_agrees_with_stage01(const Scene& scene, const char* what, float expected_at_least, int spp = 1) {
    const int width = 48, height = 36;
    RenderSettings settings = test_frame_settings(scene, width, height, true);
    settings.spp = spp;
    settings.record_hits = false;
    const FrameResult gpu = render_hybrid(scene, settings, kBruteForce);
    const Image cpu = render_stage01(scene, settings);
    std::size_t failing = 0;
    float brightest = 0.0f;
    for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
        bool bad = false;
        for (int c = 0; c < 3; ++c) {
            const float g = gpu.image.pixels[i][c], e = cpu.pixels[i][c];
            ASSERT_TRUE(std::isfinite(g) && g >= 0.0f) << what << ": pixel " << i << " = " << g;
            brightest = std::max(brightest, g);
            if (std::abs(g - e) > 1e-3f * std::max(std::abs(e), 1e-3f)) bad = true;
        }
        failing += bad;
    }
    std::printf("%s: brightest %g, %zu of %zu pixels beyond 1e-3 relative\n", what, double(brightest), failing,
                cpu.pixels.size());
    EXPECT_GE(brightest, expected_at_least) << what;
    EXPECT_LE(double(failing), 0.005 * double(cpu.pixels.size())) << what;
}

TEST(RadianceSum, PointLightOf1e7CandelaAgreesWithStage01) {
    expect_agrees_with_stage01(bright_scene(LightType::Point, 1e7f, 48, 36), "1e7 cd point light", 1e6f);
}

TEST(RadianceSum, SunOf1e5LuxAgreesWithStage01) {
    expect_agrees_with_stage01(bright_scene(LightType::Directional, 1e5f, 48, 36), "1e5 lux sun", 1e5f);
}

// BLEND weights a surface's terms by its coverage even where no ray bounces (max depth 0, no mirror, no glass): the
// shade pass then has no slots for secondary rays and must not write any (it once cleared two blocks of flags there,
// which were the lights' shadow slots: the shadow rays were counted, never traced, and the lit image went dark,
// brightest 0.024 instead of 1.5). Every ray counted is traced: one hit record each.
TEST(RadianceSum, BlendWithoutBouncesTracesEveryShadowRay) {
    const Scene scene = builtin_scene_for("cutouts", 48, 36);
    RenderSettings settings = test_frame_settings(scene, 48, 36);
    settings.max_depth = 0;
    settings.effects.reflections = settings.effects.refractions = false;
    ASSERT_TRUE(settings.effects.blend && settings.effects.shadows);
    const FrameResult r = render_hybrid(scene, settings, kBruteForce);
    EXPECT_GT(r.stats.counters.rays[int(RayKind::Shadow)], 1000u);
    EXPECT_EQ(r.hits.size(), traced_rays(r));
    float brightest = 0.0f;
    for (const glm::vec3& p : r.image.pixels) brightest = std::max({brightest, p.r, p.g, p.b});
    EXPECT_GT(brightest, 1.0f);
}

// Beyond 2^63 per sample a channel saturates at 2^63: never negative, never wrapped.
TEST(RadianceSum, BeyondItsRangeSaturatesInsteadOfWrapping) {
    const Scene scene = bright_scene(LightType::Directional, 1e30f, 32, 24);
    const FrameResult r = render_hybrid(scene, test_frame_settings(scene, 32, 24, true), kBruteForce);
    float brightest = 0.0f;
    for (const glm::vec3& p : r.image.pixels)
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(p[c]) && p[c] >= 0.0f) << p[c];
            brightest = std::max(brightest, p[c]);
        }
    EXPECT_EQ(brightest, 9.2233720e18f);
}

// Many samples of a bright scene: each sample's sum is exact and the float sum over samples cannot wrap; the mean
// agrees with stage 01's mean over the same sample positions.
TEST(RadianceSum, ManySamplesOfABrightSceneDoNotOverflow) {
    expect_agrees_with_stage01(bright_scene(LightType::Point, 1e7f, 48, 36), "1e7 cd point light, 8 spp", 1e6f, 8);
}

// Brute force as a batch traversal (stage 02's: brute_force_traversal.h), in slices of 7 triangles so every pass
// takes several dispatches: exactly what one loop over all triangles per ray gives (same hits, ties, counts).
TEST(BatchTraversal, BruteForceInSlicesGivesIdenticalImagesHitsAndCounts) {
    gpu::BruteForceTraversal sliced(7);
    for (const char* name : {"whitted", "cornell"}) {
        const Scene scene = builtin_scene_for(name, 64, 48);
        const std::size_t triangles = scene.triangle_count();
        ASSERT_GT(triangles, 14u) << name;
        const RenderSettings settings = test_frame_settings(scene, 64, 48, true);
        const FrameResult per_ray = render_hybrid(scene, settings, kBruteForce);
        const int before = sliced.dispatches();
        const FrameResult batched = render_hybrid(scene, settings, sliced);
        EXPECT_GE(sliced.dispatches() - before, int((triangles + 6) / 7)) << name;
        expect_same_frame(per_ray, batched, true);
    }
}

// The runs a batch traversal is given (RayRun) are the batch's maximal runs of one kind (and one light), in order,
// covering it: what stage 04 builds one hierarchy per. Checked against the rays themselves on whitted (reflections,
// refractions), on eight lights under a tiny storage limit (shade runs of one light each), and on whitted with its
// opaque surfaces made BLEND, where transparency rays and refraction rays come from the same batch of hits.
Scene many_lights_scene(int width, int height);

TEST(BatchTraversal, RunsAreTheBatchsMaximalRunsOfOneKindAndLight) {
    std::set<std::pair<RayKind, std::uint32_t>> seen;
    int batches = 0;
    const auto check = [&](const gpu::BatchTraceInputs& in) {
        ++batches;
        const std::vector<gpu::WavefrontRay> rays = in.rays.download<gpu::WavefrontRay>(in.count, in.first);
        const std::vector<gpu::RayRun> expected = gpu::ray_runs(rays, 0, rays.size());
        for (const gpu::RayRun& run : expected) seen.insert({run.kind, run.light});
        ASSERT_EQ(in.runs.size(), expected.size()) << "batch " << batches;
        for (std::size_t r = 0; r < expected.size(); ++r) {
            EXPECT_EQ(in.runs[r].first, expected[r].first) << "batch " << batches << ", run " << r;
            EXPECT_EQ(in.runs[r].count, expected[r].count) << "batch " << batches << ", run " << r;
            EXPECT_EQ(in.runs[r].kind, expected[r].kind) << "batch " << batches << ", run " << r;
            EXPECT_EQ(in.runs[r].light, expected[r].light) << "batch " << batches << ", run " << r;
        }
    };
    // Brute force, each batch's runs checked against its rays before it is traced.
    struct Checked final : gpu::Traversal {
        explicit Checked(const decltype(check)& c) : check_runs(c) {}
        void trace_batch(const gpu::BatchTraceInputs& in, bool shadow) override {
            check_runs(in);
            brute.trace_batch(in, shadow);
        }
        const decltype(check)& check_runs;
        gpu::BruteForceTraversal brute{1u << 20};
    } checked(check);

    Scene blend = builtin_scene_for("whitted", 64, 48);
    for (Material& m : blend.materials)
        if (m.transmission == 0.0f) {
            m.alpha_mode = AlphaMode::Blend;
            m.base_color.a = 0.5f;
        }
    const std::pair<Scene, std::size_t> cases[] = {{builtin_scene_for("whitted", 64, 48), 0},
                                                   {many_lights_scene(64, 48), 48 << 10},
                                                   {blend, 0}};
    for (const auto& [scene, limit] : cases) {
        render_hybrid(scene, test_frame_settings(scene, 64, 48), checked, limit);
    }
    EXPECT_GT(batches, 10);
    for (RayKind k : {RayKind::Reflection, RayKind::Refraction, RayKind::Transparency})
        EXPECT_TRUE(seen.count({k, 0u})) << ray_kind_name(k);
    EXPECT_TRUE(seen.count({RayKind::Shadow, 7u}));
}

// Whitted with eight lights (the scene's own, then copies moved around): shading runs once per light when the
// shadow slots of all lights do not fit.
Scene many_lights_scene(int width, int height) {
    Scene scene = builtin_scene_for("whitted", width, height);
    const Light original = scene.lights.at(0);
    for (int i = 1; i < 8; ++i) {
        Light l = original;
        l.intensity *= 0.25f;
        l.position += glm::vec3(0.3f * float(i), 0.1f * float(i), -0.2f * float(i));
        scene.lights.push_back(l);
    }
    return scene;
}

TEST(StorageLimit, TinyLimitGivesIdenticalImageCountsAndHits) {
    const Scene scene = many_lights_scene(64, 48);
    const RenderSettings settings = test_frame_settings(scene, 64, 48, true);
    const FrameResult unlimited = render_hybrid(scene, settings, kBruteForce);
    // 48 KiB: the radiance sums of 2 of the 6 rows of 8x8 tiles (18432 bytes per row), 256 hits per batch, and one
    // light's shadow rays per shade run next to the reflection and refraction slots.
    const FrameResult tiny = render_hybrid(scene, settings, kBruteForce, 48 << 10);
    expect_same_frame(unlimited, tiny, false);
    EXPECT_GT(unlimited.stats.counters.rays[int(RayKind::Shadow)], 0u);
    // It did run in batches: bands of rows, several primary batches per band, and shade runs per light.
    const auto dispatches = [](const FrameResult& r, const char* pass) {
        return int(r.extra["pass_dispatches"][pass]);
    };
    EXPECT_EQ(dispatches(unlimited, "primary_hits"), 1);
    EXPECT_EQ(dispatches(tiny, "resolve"), 3);
    EXPECT_EQ(dispatches(tiny, "primary_hits"), 12);   // 16 tiles per band, 4 per batch
    EXPECT_GT(dispatches(tiny, "shade"), 2 * dispatches(unlimited, "shade"));
}

// Traced primary rays (stage 03 with --primary trace): camera rays in tile order, batches of tiles under a tiny limit.
FrameResult render_traced(const Scene& scene, const RenderSettings& settings, std::size_t max_storage_bytes) {
    gpu::test_context();
    gpu::GpuScene gpu_scene;
    gpu_scene.upload(scene);
    gpu::Wavefront wavefront(kBruteForce);
    wavefront.max_storage_bytes = max_storage_bytes;
    wavefront.begin_frame(gpu_scene, settings);
    wavefront.trace_camera_sample(glm::vec2(0.5f));
    FrameResult result;
    wavefront.finish_frame(result);
    return result;
}

TEST(StorageLimit, TracedPrimaryRaysUnderATinyLimitGiveTheSameFrame) {
    const Scene scene = many_lights_scene(64, 48);
    const RenderSettings settings = test_frame_settings(scene, 64, 48, true);
    const FrameResult unlimited = render_traced(scene, settings, 0);
    const FrameResult tiny = render_traced(scene, settings, 48 << 10);
    expect_same_frame(unlimited, tiny, false);
    std::size_t primaries = 0;
    for (const HitRecord& h : unlimited.hits)
        primaries += ray_kind(h.kind_light) == RayKind::Primary;
    EXPECT_EQ(primaries, 64u * 48u);
}

TEST(StorageLimit, ImageBeyondTheLimitIsRefusedWithAClearError) {
    const Scene scene = builtin_scene_for("diffuse", 64, 48);
    try {
        render_hybrid(scene, test_frame_settings(scene, 64, 48, true), kBruteForce, 16 << 10);   // a row of tiles: 18432
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("storage block limit"), std::string::npos) << e.what();
    }
}

// llvmpipe ends an invocation's loops after 65,535 iterations in all; brute force over spheres:300's 67,202
// triangles loops longer for each shadow ray. The frame must then be refused with a message, never returned with
// rays that silently missed (wf_check_loop_budget). On a driver without the limit the same frame renders.
TEST(LoopBudget, AFrameWhoseLoopsTheDriverCutsShortIsRefusedNotWrong) {
    gpu::test_context();
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool llvmpipe = renderer && std::string(renderer).find("llvmpipe") != std::string::npos;
    const Scene scene = builtin_scene_for("spheres:300", 16, 12);
    ASSERT_GT(scene.triangle_count(), 65535u);
    RenderSettings settings = test_frame_settings(scene, 16, 12, true);
    if (llvmpipe) {
        try {
            render_hybrid(scene, settings, kBruteForce);
            FAIL() << "a frame whose loops llvmpipe cut short was returned";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("65,535 loop iterations"), std::string::npos) << e.what();
        }
    } else {
        EXPECT_GT(render_hybrid(scene, settings, kBruteForce).stats.counters.intersection_tests, 0u);
    }
    // Within the budget the probe stays silent: the whitted scene renders (every other test renders too).
    const Scene small = builtin_scene_for("whitted", 16, 12);
    EXPECT_NO_THROW(render_hybrid(small, test_frame_settings(small, 16, 12, true), kBruteForce));
}

}  // namespace
}  // namespace rt
