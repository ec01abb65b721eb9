#include "stats.h"

#include <fstream>
#include <stdexcept>

#include "common/scene/whole_file.h"
#include "atomic_file.h"

namespace rt {

void FrameStats::add(const FrameStats& o) {
    counters.add(o.counters);
    rasterized_rays += o.rasterized_rays;
    upload_ms += o.upload_ms;
    build_ms += o.build_ms;
    raster_ms += o.raster_ms;
    trace_ms += o.trace_ms;
    shade_ms += o.shade_ms;
    compile_ms += o.compile_ms;
    total_ms += o.total_ms;
}

nlohmann::json make_stats_json(const std::string& stage, const std::string& scene, int width, int height,
                               const std::string& renderer, const std::vector<std::string>& effects,
                               const FrameStats& s, const nlohmann::json& extra) {
    nlohmann::json j;
    j["stage"] = stage;
    j["scene"] = scene;
    j["width"] = width;
    j["height"] = height;
    j["renderer"] = renderer;
    j["effects"] = effects;
    j["rays"] = {{"primary", s.counters.rays[int(RayKind::Primary)]},
                 {"rasterized", s.rasterized_rays},
                 {"shadow", s.counters.rays[int(RayKind::Shadow)]},
                 {"reflection", s.counters.rays[int(RayKind::Reflection)]},
                 {"refraction", s.counters.rays[int(RayKind::Refraction)]},
                 {"transparency", s.counters.rays[int(RayKind::Transparency)]},
                 // of the shadow rays, those to a cell of an area light's grid (common/trace/area_light.h)
                 {"light_samples", s.counters.light_samples}};
    j["traced_rays"] = s.traced_rays();
    j["intersection_tests"] = s.counters.intersection_tests;
    // Where they come from: the rays of each kind made these (primary: the primary-hit pass of the rasterizing
    // stages, or the traced camera rays). They sum to intersection_tests.
    for (int k = 0; k < kRayKinds; ++k)
        j["intersection_tests_by_kind"][ray_kind_name(RayKind(k))] = s.counters.tests_by_kind[k];
    j["time_ms"] = {{"upload", s.upload_ms}, {"build", s.build_ms}, {"raster", s.raster_ms}, {"trace", s.trace_ms},
                    {"shade", s.shade_ms},   {"compile", s.compile_ms}, {"total", s.total_ms}};
    j["mrays_per_s"] = s.mrays_per_s();
    if (extra.is_object()) j.update(extra);
    return j;
}

void write_json(const std::string& path, const nlohmann::json& json) {
    const std::string tmp = temporary_sibling(path);
    try {
        write_whole_file(tmp, json.dump(2) + "\n");
    } catch (const std::runtime_error& e) {
        discard_temporary(tmp);
        throw std::runtime_error("cannot write " + path + ": " + e.what());
    }
    commit_temporary(tmp, path);
}

std::string cpu_model_name() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.starts_with("model name")) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
        }
    return "unknown CPU";
}

}  // namespace rt
