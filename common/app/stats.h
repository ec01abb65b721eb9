// What every stage reports: the stats JSON (--stats FILE.json) and the summary line.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../trace/ray.h"

namespace rt {

struct FrameStats {
    RayCounters counters;
    double build_ms = 0;   // acceleration structures, uploads, G-buffer rasterization setup
    double trace_ms = 0;   // everything that traces and shades
    double total_ms = 0;   // wall clock of the frame, build + trace + overheads (excluding image writing)
    double mrays_per_s() const {
        return trace_ms > 0 ? double(counters.total_rays()) / (trace_ms * 1e3) : 0.0;
    }
};

// Builds the JSON document with the keys shared by every stage (see the README, "Stats JSON"): stage, scene, width,
// height, renderer, effects, rays{primary,shadow,reflection,refraction}, intersection_tests,
// time_ms{build,trace,total}, mrays_per_s. `extra` is merged in last (stage-specific keys, defaults, settings).
nlohmann::json make_stats_json(const std::string& stage, const std::string& scene, int width, int height,
                               const std::string& renderer, const std::vector<std::string>& effects,
                               const FrameStats& stats, const nlohmann::json& extra = {});

// Writes JSON atomically (temporary file + rename). Throws std::runtime_error.
void write_json(const std::string& path, const nlohmann::json& json);

// The CPU's model name from /proc/cpuinfo (the "renderer" of CPU stages).
std::string cpu_model_name();

}  // namespace rt
