#include "driver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "../scene/builtin_scenes.h"
#include "../scene/gltf_io.h"
#include "options.h"
#include "progress.h"

namespace rt {

namespace {

// Errors the user can fix (bad options, bad scene, bad output path): exit code 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

SceneAsset load_scene(const std::string& spec, bool quiet) {
    if (spec.starts_with("builtin:")) return make_builtin_scene(spec.substr(8));
    if (!std::filesystem::exists(spec)) throw InputError("scene file not found: " + spec);
    std::string warnings;
    SceneAsset asset = load_gltf(spec, &warnings);
    if (!warnings.empty() && !quiet) std::cerr << "warning: " << warnings << "\n";
    return asset;
}

std::string scene_label(const std::string& spec) {
    if (spec.starts_with("builtin:")) return spec.substr(8);
    return std::filesystem::path(spec).stem().string();
}

const char* name_of(IntersectMethod m) { return m == IntersectMethod::Watertight ? "watertight" : "moller"; }
const char* name_of(OffsetMethod m) { return m == OffsetMethod::Robust ? "robust" : "epsilon"; }
const char* name_of(FresnelMode m) { return m == FresnelMode::Exact ? "exact" : "schlick"; }

nlohmann::json settings_json(const RenderSettings& s) {
    return {{"max_depth", s.max_depth}, {"spp", s.spp},         {"cutoff", s.cutoff},
            {"intersect", name_of(s.intersect)}, {"offset", name_of(s.offset)}, {"epsilon", s.epsilon},
            {"fresnel", name_of(s.fresnel)}};
}

void print_summary(const std::string& stage, const std::string& scene, const RenderSettings& s, const FrameStats& f,
                   const std::string& out) {
    const double rays = double(f.counters.total_rays());
    std::printf("%s: %s %dx%d  %.1f ms  %.0f rays  %.2f Mrays/s  %.1f tests/ray%s%s\n", stage.c_str(), scene.c_str(),
                s.width, s.height, f.total_ms, rays, f.mrays_per_s(),
                rays > 0 ? double(f.counters.intersection_tests) / rays : 0.0, out.empty() ? "" : "  -> ",
                out.c_str());
    std::fflush(stdout);
}

int run(const std::string& stage, int argc, char** argv, Renderer& renderer) {
    CLI::App app{stage + ": one stage of the ray-tracing course (see " + stage + "/README.md)", stage};
    app.set_version_flag("--version", std::string("raytracing course ") + stage);
    Options options;
    add_shared_options(app, options);
    renderer.add_options(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line, CLI11's message, then exit 2.
        throw InputError(e.what());
    }
    try {
        validate_options(options);
    } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
    }

    SceneAsset asset;
    try {
        asset = load_scene(options.scene, options.render.quiet);
    } catch (const SceneError& e) {
        throw InputError(e.what());
    }
    if (options.camera >= int(asset.cameras.size()) && options.camera >= 0)
        throw InputError("--camera " + std::to_string(options.camera) + ": the scene has " +
                         std::to_string(asset.cameras.size()) + " camera(s)");
    if (!options.export_path.empty()) {
        save_gltf(asset, options.export_path);
        if (!options.render.quiet) std::printf("%s: exported %s\n", stage.c_str(), options.export_path.c_str());
        if (options.out.empty() && options.stats.empty()) return 0;
    }

    renderer.initialize();
    const std::string label = scene_label(options.scene);
    FrameStats total;
    nlohmann::json frames = nlohmann::json::array();
    nlohmann::json last_extra;
    std::vector<std::string> effect_names;
    Scene scene;
    std::size_t dropped = 0;
    float duration = 0.0f;
    for (const Animation& a : asset.animations) duration = std::max(duration, a.duration());
    for (int frame = 0; frame < options.frames || renderer.interactive(); ++frame) {
        // Past the requested frames only an interactive window keeps going: nothing more is written, and animated
        // scenes loop.
        const bool extra = frame >= options.frames;
        FlattenOptions flatten_options;
        flatten_options.time = float(frame / options.fps);
        if (extra && duration > 0.0f) flatten_options.time = std::fmod(flatten_options.time, duration);
        flatten_options.camera = options.camera;
        flatten_options.max_triangles = options.max_triangles;
        flatten_options.aspect = float(options.render.width) / float(options.render.height);
        try {
            scene = flatten(asset, flatten_options, &dropped);
        } catch (const std::out_of_range& e) {
            throw InputError(std::string("--camera: ") + e.what());
        }
        if (dropped > 0 && frame == 0 && !options.render.quiet)
            std::cerr << "warning: dropped " << dropped << " triangle(s) with non-finite vertices\n";
        RenderSettings settings = options.render;
        try {
            settings.effects = resolve_effects(options.effects, scene);
        } catch (const std::invalid_argument& e) {
            throw InputError(e.what());
        }
        effect_names = settings.effects.names();

        const auto start = std::chrono::steady_clock::now();
        FrameResult result = renderer.render(scene, settings);
        result.stats.total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

        if (extra) continue;
        const std::string path = options.out.empty() ? "" : frame_path(options.out, frame, options.frames);
        if (!path.empty()) write_image(path, result.image);
        if (!options.render.quiet) print_summary(stage, label, settings, result.stats, path);
        total.counters.add(result.stats.counters);
        total.build_ms += result.stats.build_ms;
        total.trace_ms += result.stats.trace_ms;
        total.total_ms += result.stats.total_ms;
        if (options.frames > 1)
            frames.push_back(make_stats_json(stage, label, settings.width, settings.height, renderer.renderer_name(),
                                             effect_names, result.stats, {{"time_s", flatten_options.time}}));
        last_extra = result.extra;
    }

    if (!options.stats.empty()) {
        nlohmann::json extra = {{"triangles", scene.triangle_count()},
                                {"lights", scene.lights.size()},
                                {"defaults", {{"camera", scene.default_camera}, {"light", scene.default_light}}},
                                {"dropped_triangles", dropped},
                                {"settings", settings_json(options.render)},
                                {"threads", resolve_thread_count(options.render.threads)},
                                {"frames", options.frames}};
        if (options.frames > 1) extra["frame_stats"] = frames;
        if (last_extra.is_object()) extra.update(last_extra);
        write_json(options.stats, make_stats_json(stage, label, options.render.width, options.render.height,
                                                  renderer.renderer_name(), effect_names, total, extra));
    }
    return 0;
}

}  // namespace

int run_stage(const std::string& stage, int argc, char** argv, Renderer& renderer) {
    try {
        return run(stage, argc, argv, renderer);
    } catch (const InputError& e) {
        std::cerr << stage << ": error: " << e.what() << "\n";
        return 2;
    } catch (const SceneError& e) {
        std::cerr << stage << ": error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << stage << ": error: " << e.what() << "\n";
        return 1;
    }
}

}  // namespace rt
