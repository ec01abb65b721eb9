// embree_rays - traces the rays of a --dump-hits file through Embree 3, a production CPU ray tracer, on all hardware
// threads: the yardstick bench_grid holds stage 03's Mrays/s against. Benchmark-only: built when CMake finds Embree
// (scripts/setup --bench installs it).
//
//     embree_rays --scene SPEC --hits FILE [--time SECONDS] [--repeat N] [--skip-primary] [--light-grid N]
//                 [--light-jitter]
//
// SPEC is what the stages take (builtin:NAME or a .gltf/.glb); --time must be the dumped frame's (frame / fps), so
// the triangles and lights are the same. --skip-primary drops the primary records (a stage that rasterized its
// primaries records them but traced none). Closest-hit records (primary, reflection, refraction) are traced with
// rtcIntersect1 over (0, inf), like the stages. The dump does not store a shadow ray's tmax, so it is rebuilt the
// way common/trace/whitted.h sets it (recorded_shadow_tmax: the distance to the record's light, infinite for a
// directional light, or to its area light's cell, for the stage's --light-grid and --light-jitter, robust offsets);
// shadow records are traced with rtcOccluded1. Only tracing is timed, best of --repeat runs.
// Prints Mrays/s and how often Embree agrees with the dump: the same closest triangle (or both a miss), the same
// occlusion.
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/app/hit_file.h"
#include "common/app/stats.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/gltf/gltf_io.h"
#include "common/scene/scene.h"
#include "common/trace/whitted.h"

namespace {

rt::Scene load_frame(const std::string& spec, float time) {
    const rt::SceneAsset asset =
        spec.starts_with("builtin:") ? rt::make_builtin_scene(spec.substr(8)) : rt::load_gltf(spec);
    rt::FlattenOptions options;
    options.time = time;
    return rt::flatten(asset, options);
}

// One Embree triangle geometry holding the flattened triangle soup, so primID is the stages' triangle id.
RTCScene build_scene(RTCDevice device, const rt::Scene& scene) {
    const std::size_t n = scene.triangle_count();
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    for (std::size_t i = 0; i < 3 * n; ++i) {
        for (int c = 0; c < 3; ++c) vertices[3 * i + c] = scene.positions[i][c];
        indices[i] = unsigned(i);
    }
    rtcCommitGeometry(geometry);
    RTCScene rtc_scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(rtc_scene, RTC_BUILD_QUALITY_HIGH);
    rtcAttachGeometry(rtc_scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(rtc_scene);
    return rtc_scene;
}

RTCRay make_ray(const rt::HitRecord& r, float tfar) {
    RTCRay ray{};
    ray.org_x = r.origin[0], ray.org_y = r.origin[1], ray.org_z = r.origin[2];
    ray.dir_x = r.direction[0], ray.dir_y = r.direction[1], ray.dir_z = r.direction[2];
    ray.tnear = 0.0f;
    ray.tfar = tfar;
    ray.mask = ~0u;
    return ray;
}

// Traces records [0, n) on `threads` threads (chunks taken from a shared counter); result[i] is the triangle id
// (closest) or 1/-1 (occluded or not), in the dump's convention.
void trace_all(RTCScene scene, const std::vector<rt::HitRecord>& records, const std::vector<float>& tfar,
               std::vector<std::int32_t>& result, std::vector<float>& result_t, unsigned threads) {
    constexpr std::size_t kChunk = 1024;
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (std::size_t begin; (begin = next.fetch_add(kChunk)) < records.size();) {
            const std::size_t end = std::min(records.size(), begin + kChunk);
            for (std::size_t i = begin; i < end; ++i) {
                const rt::HitRecord& r = records[i];
                if (rt::ray_kind(r.kind_light) == rt::RayKind::Shadow) {
                    RTCRay ray = make_ray(r, tfar[i]);
                    rtcOccluded1(scene, &context, &ray);
                    result[i] = ray.tfar < 0.0f ? 1 : -1;  // Embree marks an occluded ray with tfar = -inf
                } else {
                    RTCRayHit rh{};
                    rh.ray = make_ray(r, tfar[i]);
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rtcIntersect1(scene, &context, &rh);
                    result[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : std::int32_t(rh.hit.primID);
                    result_t[i] = rh.ray.tfar;
                }
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (std::thread& t : pool) t.join();
}

int usage(const char* message) {
    std::fprintf(stderr, "embree_rays: error: %s\nusage: embree_rays --scene SPEC --hits FILE [--time S] [--repeat N] [--skip-primary]\n",
                 message);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string spec, hits_path;
    float time = 0.0f;
    int repeat = 5;
    bool skip_primary = false;
    rt::LightGrid grid;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--skip-primary" || arg == "--light-jitter") {
            (arg == "--skip-primary" ? skip_primary : grid.jitter) = true;
            continue;
        }
        if (i + 1 >= argc) return usage(("missing value for " + arg).c_str());
        if (arg == "--scene") spec = argv[++i];
        else if (arg == "--hits") hits_path = argv[++i];
        else if (arg == "--time") time = std::stof(argv[++i]);
        else if (arg == "--repeat") repeat = std::max(1, std::stoi(argv[++i]));
        else if (arg == "--light-grid") {
            grid.n = std::stoi(argv[++i]);
            if (grid.n < 1 || grid.n > rt::kMaxLightGrid) return usage("--light-grid must be 1 to 16");
        }
        else return usage(("unknown option " + arg).c_str());
    }
    if (spec.empty() || hits_path.empty()) return usage("--scene and --hits are required");

    rt::Scene scene;
    std::vector<rt::HitRecord> records;
    std::vector<float> tfar;
    try {
        scene = load_frame(spec, time);
        records = rt::read_hit_file(hits_path);
        if (skip_primary)
            std::erase_if(records, [](const rt::HitRecord& r) {
                return rt::ray_kind(r.kind_light) == rt::RayKind::Primary;
            });
        for (const rt::HitRecord& r : records)
            tfar.push_back(rt::ray_kind(r.kind_light) != rt::RayKind::Shadow ? std::numeric_limits<float>::infinity()
                           : rt::light_index(r.kind_light) >= scene.light_count()
                               ? throw std::runtime_error("a shadow record names light " +
                                                          std::to_string(rt::light_index(r.kind_light)))
                               : rt::recorded_shadow_tmax(scene, grid, rt::OffsetMethod::Robust,
                                                          rt::kDefaultEpsilon, r));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "embree_rays: error: %s\n", e.what());
        return 2;
    }

    RTCDevice device = rtcNewDevice(nullptr);
    const auto build_start = std::chrono::steady_clock::now();
    RTCScene rtc_scene = build_scene(device, scene);
    const double build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - build_start).count();

    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::int32_t> result(records.size());
    std::vector<float> result_t(records.size(), 0.0f);
    double best_ms = std::numeric_limits<double>::infinity();
    for (int run = 0; run < repeat; ++run) {
        const auto start = std::chrono::steady_clock::now();
        trace_all(rtc_scene, records, tfar, result, result_t, threads);
        best_ms = std::min(best_ms, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }

    // A closest hit on another triangle at the same distance (within 1e-6 relative) is a tie between overlapping
    // surfaces: the stages take the lowest triangle id, Embree any of them. Counted apart, as "ties".
    std::size_t closest = 0, closest_same = 0, closest_ties = 0, shadow = 0, shadow_same = 0;
    for (std::size_t i = 0; i < records.size(); ++i) {
        const bool is_shadow = rt::ray_kind(records[i].kind_light) == rt::RayKind::Shadow;
        (is_shadow ? shadow : closest)++;
        if (result[i] == records[i].triangle) (is_shadow ? shadow_same : closest_same)++;
        else if (!is_shadow && result[i] >= 0 && records[i].triangle >= 0 &&
                 std::abs(result_t[i] - records[i].t) <= 1e-6f * std::abs(records[i].t))
            ++closest_ties;
    }
    auto percent = [](std::size_t a, std::size_t b) { return b ? 100.0 * double(a) / double(b) : 100.0; };
    std::printf("embree_rays: %s, %zu triangles, Embree %s build (high quality) %.1f ms\n", spec.c_str(),
                scene.triangle_count(), RTC_VERSION_STRING, build_ms);
    std::printf("embree_rays: %zu rays (%zu closest, %zu shadow), %u threads on %s, best of %d: %.3f ms\n",
                records.size(), closest, shadow, threads, rt::cpu_model_name().c_str(), repeat, best_ms);
    std::printf("embree_rays: agreement with the dump: closest %zu/%zu (%.3f%%), shadow %zu/%zu (%.3f%%)\n", closest_same,
                closest, percent(closest_same, closest), shadow_same, shadow, percent(shadow_same, shadow));
    std::printf("embree_rays: closest hits on another triangle at the same t (ties): %zu\n", closest_ties);
    std::printf("mrays_per_s %.3f\n", best_ms > 0.0 ? double(records.size()) / (best_ms * 1e3) : 0.0);

    rtcReleaseScene(rtc_scene);
    rtcReleaseDevice(device);
    return 0;
}
