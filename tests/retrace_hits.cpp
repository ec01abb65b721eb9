// retrace_hits --rays A.hits [stage options] --dump-hits B.hits: every ray recorded in A (another stage's
// --dump-hits), traced once more by stage 01's brute force from the very same origin and direction, its hit in B.
//
// Why: hits.02_raster_hybrid.* compares 02 with 01_naive's own render, ray by ray along each path. A GPU whose
// division and square roots are not correctly rounded (GLSL 4.50 allows 2.5 ulps for a / b, 2 for inversesqrt; only
// llvmpipe rounds them like the CPU) spawns each secondary ray a few ulps away from the CPU's, and the difference
// grows along the path: on an NVIDIA H200, 12 of 14 scenes had rays thousands of ulps apart (docs/gpu-nvidia.md).
// Retracing 02's own rays separates the two questions: given this exact ray, does the GPU find the hit brute force
// finds? That holds on every driver, with only the division in t left to differ (README, "Exact hit checks").
//
// Shadow rays get the tmax the stages give them: the distance from their origin to their light, or none for a
// directional light (whitted.h, shadow_tmax); to an area light, the distance to the cell's sample moved off the light
// (area_light.h, area_shadow_tmax; --light-grid and --light-jitter as the stage's). The scene, its frame time and its effects come from the same options as
// the stage's (--frames N: every frame retraces the same rays; the test reads the last).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "01_naive/brute_force_tracer.h"
#include "common/app/driver.h"
#include "common/app/hit_file.h"
#include "common/app/input_error.h"
#include "common/trace/whitted.h"

namespace rt {
namespace {

class RetraceRenderer : public Renderer {
public:
    void add_options(CLI::App& app) override {
        app.add_option("--rays", rays_path_, "The --dump-hits file whose rays to trace again")->required();
    }
    void initialize() override {
        try {
            rays_ = read_hit_file(rays_path_);
        } catch (const std::exception& e) {
            throw InputError(e.what());
        }
    }
    std::string renderer_name() const override { return "CPU brute force (retrace_hits)"; }
    std::string unsupported(const Scene& scene, const RenderSettings& settings) const override {
        if (!settings.record_hits) return "retrace_hits writes nothing without --dump-hits";
        for (const HitRecord& r : rays_)
            if (ray_kind(r.kind_light) == RayKind::Shadow) {
                const std::uint32_t light = light_index(r.kind_light);
                if (light >= scene.light_count())
                    return "a shadow ray of " + rays_path_ + " names light " + std::to_string(light) +
                           "; the scene has " + std::to_string(scene.light_count()) + " light(s)";
                if (light >= scene.lights.size() && light_sample(r.kind_light) >= settings.light_grid.cells())
                    return "a shadow ray of " + rays_path_ + " names cell " + std::to_string(light_sample(r.kind_light)) +
                           " of area light " + std::to_string(light) + "; --light-grid " +
                           std::to_string(settings.light_grid.n) + " has " + std::to_string(settings.light_grid.cells());
            }
        return {};
    }

    FrameResult render(const Scene& scene, const RenderSettings& settings) override {
        // The tracers of 01_naive's renderer: BLEND read as coverage for closest hits, the cut-out rule for shadows.
        const BruteForceTracer<float> tracer(scene, settings.intersect, settings.effects.cutouts,
                                             settings.effects.blend);
        const BruteForceTracer<float> shadow_tracer(scene, settings.intersect, settings.effects.cutouts, false);
        FrameResult result;
        result.hits.reserve(rays_.size());
        RayCounters counters;
        for (const HitRecord& r : rays_) {
            Ray<float> ray;
            ray.origin = glm::vec3(r.origin[0], r.origin[1], r.origin[2]);
            ray.direction = glm::vec3(r.direction[0], r.direction[1], r.direction[2]);
            HitRecord out = r;
            if (ray_kind(r.kind_light) == RayKind::Shadow) {
                ray.tmax = recorded_shadow_tmax(scene, settings.light_grid, settings.offset, settings.epsilon, r);
                out.triangle = shadow_tracer.occluded(ray, counters) ? 1 : -1;
                out.t = 0.0f;
            } else {
                Hit<float> hit;
                tracer.closest(ray, hit, counters);
                out.triangle = hit.triangle;
                out.t = hit.valid() ? hit.t : 0.0f;
            }
            result.hits.push_back(out);
        }
        result.stats.counters = counters;
        return result;
    }

private:
    std::string rays_path_;
    std::vector<HitRecord> rays_;
};

}  // namespace
}  // namespace rt

int main(int argc, char** argv) {
    rt::RetraceRenderer renderer;
    return rt::run_stage("retrace_hits", argc, argv, renderer);
}
