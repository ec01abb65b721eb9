#include "naive_renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>

#include <CLI/CLI.hpp>

#include "01_naive/brute_force_tracer.h"
#include "common/app/options.h"
#include "common/app/pixel_samples.h"
#include "common/app/parallel_rows.h"
#include "common/app/progress.h"
#include "common/trace/whitted.h"

namespace rt {

namespace {

template <class T>
FrameResult render_with(const Scene& scene, const RenderSettings& settings) {
    FrameResult result;
    result.image = Image(settings.width, settings.height);
    const auto t0 = std::chrono::steady_clock::now();
    // With BLEND read as coverage, closest-hit rays see a BLEND surface wherever it covers anything while shadow
    // rays keep the cut-out (opacity.h): a second tracer with the shadow rule.
    const BruteForceTracer<T> tracer(scene, settings.intersect, settings.effects.cutouts, settings.effects.blend);
    std::optional<BruteForceTracer<T>> shadow_tracer;
    if (settings.effects.blend) shadow_tracer.emplace(scene, settings.intersect, settings.effects.cutouts, false);
    const auto t1 = std::chrono::steady_clock::now();

    WhittedSettings ws;
    ws.max_depth = settings.max_depth;
    ws.cutoff = settings.cutoff;
    ws.fresnel = settings.fresnel;
    ws.offset = settings.offset;
    ws.epsilon = settings.epsilon;
    ws.effects = settings.effects;
    ws.light_grid = settings.light_grid;
    const Whitted<T, BruteForceTracer<T>> whitted(scene, tracer, ws, shadow_tracer ? &*shadow_tracer : nullptr);
    const std::vector<glm::vec2> samples = pixel_sample_offsets(settings.spp);

    // Diagnostics: each row records its own hits (rows run in parallel), joined in row order afterwards.
    std::vector<std::vector<HitRecord>> row_hits(settings.record_hits ? std::size_t(settings.height) : 0);
    if (settings.record_tests_per_pixel)
        result.tests_per_pixel.assign(std::size_t(settings.width) * std::size_t(settings.height), 0);

    Progress progress("01_naive", settings.height, !settings.quiet);
    parallel_rows(settings.height, resolve_thread_count(settings.threads), progress, result.stats.counters,
                  [&](int y, RayCounters& counters) {
                      std::vector<HitRecord>* row = row_hits.empty() ? nullptr : &row_hits[std::size_t(y)];
                      for (int x = 0; x < settings.width; ++x) {
                          const std::uint32_t pixel = std::uint32_t(y * settings.width + x);
                          // --pixel without --dump-hits records only that pixel's rays.
                          std::vector<HitRecord>* hits =
                              settings.record_hits_pixel < 0 || settings.record_hits_pixel == std::int64_t(pixel)
                                  ? row
                                  : nullptr;
                          const std::uint64_t tests_before = counters.intersection_tests;
                          glm::vec3 sum(0.0f);
                          for (std::size_t i = 0; i < samples.size(); ++i) {
                              const Ray<T> ray = camera_ray<T>(scene.camera, settings.width, settings.height,
                                                               T(x) + T(samples[i].x), T(y) + T(samples[i].y));
                              counters.rays[int(RayKind::Primary)]++;
                              // --pixel: the watched pixel's rays also report what they cost.
                              std::vector<RayWork>* work =
                                  std::int64_t(pixel) == settings.watch_pixel ? &result.ray_work : nullptr;
                              const HitLog log{hits, std::uint32_t(i), pixel, work};
                              const HitLog* logged = hits || work ? &log : nullptr;
                              // One bound for every stage: a sample saturates at 2^63, as the GPU's fixed-point sum.
                              sum += glm::min(whitted.radiance(ray, 0, glm::vec3(1.0f), counters, logged, 1,
                                                               std::nullopt, {pixel, std::uint32_t(i)}),
                                              glm::vec3(kMaxSampleRadiance));
                          }
                          result.image.at(x, y) = sum / float(samples.size());
                          if (settings.record_tests_per_pixel)
                              result.tests_per_pixel[pixel] = std::uint32_t(std::min<std::uint64_t>(
                                  counters.intersection_tests - tests_before, UINT32_MAX));
                      }
                  });
    for (std::vector<HitRecord>& row : row_hits) result.hits.insert(result.hits.end(), row.begin(), row.end());
    progress.finish();
    const auto t2 = std::chrono::steady_clock::now();
    result.stats.build_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    result.stats.trace_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();
    result.extra["precision"] = sizeof(T) == sizeof(double) ? "double" : "float";
    return result;
}

}  // namespace

void NaiveRenderer::add_options(CLI::App& app) {
    add_enum(app, "--precision", precision, {{"float", Precision::Float}, {"double", Precision::Double}},
             "Arithmetic of the ray/triangle tests and hit points");
}

std::string NaiveRenderer::renderer_name() const { return cpu_model_name(); }

FrameResult NaiveRenderer::render(const Scene& scene, const RenderSettings& settings) {
    return precision == Precision::Double ? render_with<double>(scene, settings) : render_with<float>(scene, settings);
}

}  // namespace rt
