#include "ray_hierarchy_renderer.h"

#include <CLI/CLI.hpp>

#include "common/app/options.h"

namespace rt {

RayHierarchyRenderer::RayHierarchyRenderer()
    : RasterizedPrimaryStage({"", {}, {},
                [this](const gpu::BatchTraceInputs& in) { trace_batch(in, false); },
                [this](const gpu::BatchTraceInputs& in) { trace_batch(in, true); },
                "leaf pairs"}) {}   // --pixel: the ray's (ray, triangle) pairs at level 0, its own node tests
RayHierarchyRenderer::~RayHierarchyRenderer() = default;

std::string RayHierarchyRenderer::unsupported(const Scene&, const RenderSettings& settings) const {
    // The leaf pass with the opacity test (cut-outs) binds 16 storage blocks, GL 4.5's guaranteed minimum and
    // llvmpipe's limit; counting tests per pixel would be the 17th, and the link fails after the compile.
    if (settings.record_tests_per_pixel && settings.effects.cutouts)
        return std::string(settings.watch_pixel >= 0 ? "--pixel" : "--heatmap") +
               ": not available in this stage for a scene with cut-outs (the leaf pass would need 17 GL "
               "storage blocks; GL 4.5 guarantees 16): use stage 03, or --effects without cutouts";
    return {};
}

void RayHierarchyRenderer::add_options(CLI::App& app) {
    RasterizedPrimaryStage::add_options(app);
    app.add_option("--branching", hierarchy_options.branching, "Children per node of the ray hierarchy: 4, 8 or 16")
        ->capture_default_str()
        ->check(whole_number_of({4, 8, 16}));
    app.add_option("--levels", hierarchy_options.levels,
                   "Upper levels of the hierarchy used above the rays (0 = all, up to a single root; default 3: with the object "
                   "tree, the levels above add node tests and steps and cull nothing more)")
        ->capture_default_str()
        ->check(whole_number_in(0, 32));
    app.add_option_function<std::string>(
           "--objects",
           [this](const std::string& s) {
               hierarchy_options.objects = s == "triangles" ? ObjectMode::triangles
                                           : s == "meshes"  ? ObjectMode::meshes
                                                            : ObjectMode::tree;
           },
           "What the top ray nodes meet: tree (default: a tree of bounding spheres over the triangles, rebuilt each "
           "frame), meshes (runs of one material, then their triangles: Reis) or triangles (every triangle: Roger et "
           "al. 2007)")
        ->check(CLI::IsMember({"tree", "meshes", "triangles"}));
    app.add_option_function<std::string>(
           "--sphere-test", [this](const std::string& s) { hierarchy_options.sphere_test = s == "on"; },
           "Test each ray against a triangle's bounding sphere before the exact ray/triangle test: on (default) or "
           "off (every (ray, triangle) pair the hierarchy leaves gets the exact test, as in the papers)")
        ->check(CLI::IsMember({"on", "off"}));
}

void RayHierarchyRenderer::build(const Scene& scene, const RenderSettings&) {
    if (!hierarchy_) hierarchy_ = std::make_unique<GpuRayHierarchy>();
    hierarchy_->options = hierarchy_options;
    hierarchy_->timer = &timer();
    hierarchy_->reset_stats();
    traced_ = false;
    // The only per-frame work on the geometry: the triangles' bounding spheres and the objects (the tree).
    auto scope = timer().scope("build");
    hierarchy_->prepare(gpu_scene(), object_ranges(scene.material_ids), scene.bounds);
}

void RayHierarchyRenderer::trace_batch(const gpu::BatchTraceInputs& in, bool shadow) {
    traced_ = true;
    hierarchy_->trace(in, shadow);
}

void RayHierarchyRenderer::render_sample(const Scene& scene, const RenderSettings& settings, glm::vec2 offset) {
    rasterize_and_shade_sample(scene, settings, offset);
}

std::vector<std::string> RayHierarchyRenderer::stage_programs() const {
    std::vector<std::string> programs = RasterizedPrimaryStage::stage_programs();
    for (std::string& p : GpuRayHierarchy::program_names()) programs.push_back(std::move(p));
    return programs;
}

void RayHierarchyRenderer::add_stage_stats(FrameResult& result) {
    const HierarchyOptions& o = hierarchy_options;
    const std::array<HierarchyKindStats, kRayKinds>& stats = hierarchy_->stats();   // the frame's one read of them
    nlohmann::json rh = {{"branching", o.branching},
                         {"levels_limit", o.levels},
                         {"objects", object_mode_name(o.objects)},
                         {"sphere_test", o.sphere_test},
                         {"object_tree",
                          {{"levels", hierarchy_->object_levels()},
                           {"nodes", hierarchy_->object_nodes()},
                           {"cluster_size", o.objects == ObjectMode::tree ? kClusterSize : 0u},
                           {"branching", o.objects == ObjectMode::tree ? kObjectBranching : 0u}}},
                         {"gpu_cpu_syncs", hierarchy_->syncs},
                         {"traced", traced_},
                         {"pair_capacity", hierarchy_->capacity()},
                         {"chunks", hierarchy_->chunks},
                         {"windows", hierarchy_->windows},
                         {"fold_rounds", hierarchy_->fold_rounds},
                         {"hit_list_prunes", hierarchy_->prunes}};
    const nlohmann::json& pass_ms = result.extra["pass_time_ms"];
    auto ms = [&](const std::string& name) { return pass_ms.contains(name) ? double(pass_ms[name]) : 0.0; };
    nlohmann::json kinds = nlohmann::json::object();
    for (int k = 1; k < kRayKinds; ++k) {
        const HierarchyKindStats& s = stats[std::size_t(k)];
        if (s.rays == 0) continue;
        nlohmann::json levels = nlohmann::json::array();
        for (std::size_t l = 0; l < s.levels.size(); ++l) {
            const HierarchyLevelStats& L = s.levels[l];
            levels.push_back({{"level", l},
                              {"nodes", L.nodes},
                              {"pairs_in", L.pairs_in},
                              {"pairs_out", L.pairs_out}});
        }
        const std::uint64_t tests = s.local_tests + s.fold_tests;
        const std::string kind = ray_kind_name(RayKind(k));
        kinds[kind] = {
            {"rays", s.rays},
            {"groups", s.groups},
            {"levels", levels},
            {"object_level", {{"pairs_in", s.object_pairs_in}, {"pairs_out", s.object_pairs_out}}},
            {"node_tests", s.node_tests()},
            {"leaf_pairs", s.leaf_pairs},
            {"sphere_tests", s.sphere_tests},
            {"local_tests", s.local_tests},
            {"fold_tests", s.fold_tests},
            {"tests_per_ray", double(tests) / double(s.rays)},
            {"node_tests_per_ray", double(s.node_tests()) / double(s.rays)},
            {"brute_force_tests", s.brute_force_tests},
            {"percent_of_brute_force",
             s.brute_force_tests ? 100.0 * double(tests) / double(s.brute_force_tests) : 0.0},
            {"time_ms",
             {{"build", ms("rh_build." + kind)},
              {"traverse", ms("rh_traverse." + kind)},
              {"local_tests", ms("rh_local." + kind)}}}};
    }
    rh["kinds"] = kinds;
    rh["fold_ms"] = ms("rh_local.fold");   // the closest-hit fold of reflection and refraction batches together
    result.extra["ray_hierarchy"] = rh;
}

}  // namespace rt
