// What every stage reports: the stats JSON (--stats FILE.json) and the summary line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/trace/ray.h"

namespace rt {

// Times are milliseconds of one frame (summed over frames in the run's stats). GPU stages measure every phase but
// compile with GPU timer queries (GL timestamps), so a phase is the GPU's time for its passes; CPU stages measure
// wall clock and have no upload, raster, shade or compile phase (their shading is inside trace).
struct FrameStats {
    RayCounters counters;              // rays by kind; primary = one per pixel and sample, traced or rasterized
    std::uint64_t rasterized_rays = 0; // of the primary rays, those resolved by rasterization instead of tracing
    double upload_ms = 0;    // the scene to the GPU
    double build_ms = 0;     // the acceleration structure (0 for brute force)
    double raster_ms = 0;    // rasterized primary visibility (the G-buffer and its primary hits)
    double trace_ms = 0;     // traversal of the traced rays (closest and any hit); CPU stages: tracing and shading
    double shade_ms = 0;     // shading: the passes that shade hits, spawn rays and resolve the image
    double compile_ms = 0;   // shader compilation (wall clock), in none of the above
    double total_ms = 0;     // wall clock of the frame (excluding image writing): all of the above and overheads

    // Rays that were traced (every ray but the rasterized ones): what a traversal is measured by.
    std::uint64_t traced_rays() const { return counters.total_rays() - rasterized_rays; }
    // Traced rays per second of trace time, in millions.
    double mrays_per_s() const { return trace_ms > 0 ? double(traced_rays()) / (trace_ms * 1e3) : 0.0; }
    // Sums counts and times (total_ms too): the stats of a run of several frames.
    void add(const FrameStats& o);
};

// Builds the JSON document with the keys shared by every stage (see the README, "Stats JSON"): stage, scene, width,
// height, renderer, effects, rays{primary,rasterized,shadow,reflection,refraction}, traced_rays,
// intersection_tests, intersection_tests_by_kind{primary,shadow,reflection,refraction}, time_ms{upload,build,raster,
// trace,shade,compile,total}, mrays_per_s. `extra` is merged in
// last (stage-specific keys, defaults, settings).
nlohmann::json make_stats_json(const std::string& stage, const std::string& scene, int width, int height,
                               const std::string& renderer, const std::vector<std::string>& effects,
                               const FrameStats& stats, const nlohmann::json& extra = {});

// Writes JSON atomically (temporary file + rename). Throws std::runtime_error.
void write_json(const std::string& path, const nlohmann::json& json);

// The CPU's model name from /proc/cpuinfo (the "renderer" of CPU stages).
std::string cpu_model_name();

}  // namespace rt
