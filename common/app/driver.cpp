#include "driver.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <system_error>

#include <sys/stat.h>

#include <CLI/CLI.hpp>

#include "common/scene/whole_file.h"
#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/gltf/gltf_io.h"
#include "common/trace/environment.h"
#include "atomic_file.h"
#include "environment_file.h"
#include "heatmap.h"
#include "hit_file.h"
#include "input_error.h"
#include "options.h"
#include "output_files.h"
#include "parallel_rows.h"
#include "progress.h"
#include "ray_tree.h"

namespace rt {

namespace {

// Lines on stdout. The reader may go away (`01_naive ... | head -c1`): SIGPIPE is ignored (run_stage), and after the
// first failed write nothing more is printed, while rendering and the output files carry on; the exit code is not
// affected.
void print(const std::string& line) {
    static bool open = true;
    if (!open) return;
    if (std::fputs(line.c_str(), stdout) < 0 || std::fflush(stdout) != 0) open = false;
}

// The scene file must be a regular file we can reach: one line naming it and the problem otherwise (a FIFO would
// hang the reader, a folder is no scene, a loop of links or an overlong name is reported as such).
void check_scene_file(const std::string& spec) {
    struct stat st {};
    if (::stat(spec.c_str(), &st) != 0) {
        const int error = errno;
        if (error == ENOENT) throw InputError("scene file not found: " + spec);
        throw InputError("cannot read scene " + spec + ": " + std::system_category().message(error));
    }
    if (S_ISDIR(st.st_mode)) throw InputError("scene " + spec + " is a folder, not a .gltf/.glb file");
    if (!S_ISREG(st.st_mode)) throw InputError("scene " + spec + " is not a regular file (a FIFO, socket or device)");
}

SceneAsset load_scene(const std::string& spec, bool quiet) {
    if (spec.starts_with("builtin:")) return make_builtin_scene(spec.substr(8));
    check_scene_file(spec);
    std::string warnings;
    SceneAsset asset;
    try {
        asset = load_gltf(spec, &warnings);
    } catch (const std::filesystem::filesystem_error& e) {
        throw InputError("cannot read scene " + spec + ": " + e.code().message());
    }
    // One line per warning, each naming the file (--quiet silences them).
    if (!quiet) {
        std::istringstream lines(warnings);
        for (std::string line; std::getline(lines, line);)
            if (!line.empty()) std::cerr << "warning: " << spec << ": " << line << "\n";
    }
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
            {"fresnel", name_of(s.fresnel)}, {"light_grid", s.light_grid.n}, {"light_jitter", s.light_grid.jitter}};
}

void print_summary(const std::string& stage, const std::string& scene, const RenderSettings& s, const FrameStats& f,
                   const std::string& out) {
    const double rays = double(f.traced_rays());   // rasterized primary rays are not traced
    char line[256];
    std::snprintf(line, sizeof line, "%s: %s %dx%d  %.1f ms  %.0f rays  %.2f Mrays/s  %.1f tests/ray", stage.c_str(),
                  scene.c_str(), s.width, s.height, f.total_ms, rays, f.mrays_per_s(),
                  rays > 0 ? double(f.counters.intersection_tests) / rays : 0.0);
    print(line + (out.empty() ? std::string() : "  -> " + out) + "\n");
}

void write_json_file(const std::string& file, const nlohmann::json& json) {
    write_whole_file(file, json.dump(2) + "\n");
}

// The run's own temporary (RunOutputs) receives the bytes; its extension is the target's, which picks the format.
void save_gltf_into(const SceneAsset& asset, const std::string& file) {
    write_whole_file(file, gltf_file_bytes(asset, file));
}

// The steps of a run, in order: parse_command_line, load_input, reserve_outputs, export_scene, then per frame
// frame_scene, frame_settings, the renderer, write_frame; last write_stats. Bad input is an InputError (exit 2)
// before anything is rendered or written; `files` removes what the run wrote unless it reaches files.keep().

// The options from the command line; a number when the run ends there (--help, --version). `app` outlives the
// call: a renderer may keep it (a GPU stage names its progress bar after it).
std::optional<int> parse_command_line(CLI::App& app, const std::string& stage, int argc, char** argv,
                                      Renderer& renderer, Options& options) {
    app.set_version_flag("--version", std::string("raytracing course ") + stage);
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
    return std::nullopt;
}

// What the run reads: the scene, and what rays leaving it see. --background replaces the scene's colour,
// --environment (read and checked completely now, before any output is touched) replaces it by a map shared by every
// frame.
struct Input {
    SceneAsset asset;
    std::shared_ptr<const Environment> environment;
};

Input load_input(const std::string& stage, const Options& options) {
    Input in;
    try {
        in.asset = load_scene(options.scene, options.render.quiet);
    } catch (const SceneError& e) {
        throw InputError(e.what());
    }
    SceneAsset& asset = in.asset;
    if (options.camera >= int(asset.cameras.size()) && options.camera >= 0)
        throw InputError("--camera " + std::to_string(options.camera) + ": the scene has " +
                         std::to_string(asset.cameras.size()) + " camera(s)");
    if (options.background) {
        asset.background = *options.background;
        asset.has_world = true;
    }
    if (options.ambient) asset.ambient = *options.ambient;
    if (!options.environment.empty()) {
        in.environment =
            load_environment(options.environment, options.environment_rotation, options.environment_intensity);
        asset.input_files.push_back(options.environment);   // no output may overwrite it
    }
    if (options.frames > 1 && asset.animations.empty() && !options.render.quiet)
        std::cerr << stage << ": warning: --frames " << options.frames
                  << " on a static scene: every frame is the same image\n";
    return in;
}

// Every output is checked, and its temporary created, before anything is rendered (of --out only the first frame's:
// the others share its folder, and a long animation should not hold thousands of empty files).
void reserve_outputs(const Options& options, const SceneAsset& asset, RunOutputs& files) {
    const std::vector<OutputPath> outputs = planned_outputs(options);
    try {
        check_outputs(outputs, asset.input_files);
        for (const OutputPath& o : outputs)
            if (o.option != "--out" || o.path == frame_path(options.out, 0, options.frames)) files.reserve(o);
    } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
    } catch (const std::filesystem::filesystem_error& e) {
        throw InputError(e.path1().string() + ": " + e.code().message());
    }
}

// --export: the scene as glTF. True when that is all the run was asked for.
bool export_scene(const std::string& stage, const Options& options, const SceneAsset& asset, RunOutputs& files) {
    if (options.export_path.empty()) return false;
    files.write({"--export", options.export_path}, [&](const std::string& file) { save_gltf_into(asset, file); });
    if (!options.render.quiet) print(stage + ": exported " + options.export_path + "\n");
    return options.out.empty() && options.stats.empty();
}

// A new Scene::still_id: one per still scene a run renders (the GPU stages keep the scene of each id resident).
std::uint64_t next_still_id() {
    static std::atomic<std::uint64_t> next{1};
    return next++;
}

// The scene at the frame's time (past the requested frames, an animation loops), with its world: the environment,
// or the default world for a file that says nothing of its world (most glTF files; docs/shading.md).
Scene frame_scene(const std::string& stage, const Options& options, const Input& in, int frame, float duration,
                  std::size_t& dropped, float& time) {
    FlattenOptions flatten_options;
    flatten_options.time = float(frame / options.fps);
    if (frame >= options.frames && duration > 0.0f) flatten_options.time = std::fmod(flatten_options.time, duration);
    flatten_options.camera = options.camera;
    flatten_options.max_triangles = options.max_triangles;
    flatten_options.area_lights = options.area_lights;
    flatten_options.aspect = float(options.render.width) / float(options.render.height);
    time = flatten_options.time;
    Scene scene;
    try {
        scene = flatten(in.asset, flatten_options, &dropped);
    } catch (const std::out_of_range& e) {
        throw InputError(std::string("--camera: ") + e.what());
    }
    scene.environment = in.environment;
    if (!in.environment && !in.asset.has_world) {
        scene.environment = default_world();
        scene.default_world = true;
    }
    if (dropped > 0 && frame == 0 && !options.render.quiet)
        std::cerr << "warning: dropped " << dropped << " triangle(s) with non-finite vertices\n";
    if (frame == 0 && !options.render.quiet)
        if (const std::string problem = working_range_problem(scene.bounds); !problem.empty())
            std::cerr << stage << ": warning: " << problem << "\n";
    return scene;
}

// The frame's settings: the options', the effects the scene calls for, and what the outputs asked for need recorded.
RenderSettings frame_settings(const Options& options, const Scene& scene, bool shown_only) {
    RenderSettings settings = options.render;
    try {
        settings.effects = resolve_effects(options.effects, scene);
    } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
    }
    settings.record_hits = !options.dump_hits.empty();
    settings.record_tests_per_pixel = !options.heatmap.empty();
    if (options.pixel) {   // its ray tree needs its rays, what each cost, and its heatmap value
        settings.watch_pixel = std::int64_t(options.pixel->y) * settings.width + options.pixel->x;
        settings.record_tests_per_pixel = true;
        if (!settings.record_hits) settings.record_hits_pixel = settings.watch_pixel;
        settings.record_hits = true;
    }
    settings.need_image = !shown_only;   // frames past the requested ones are only shown
    // The headlight's brightness is a guess from the view axis (docs/shading.md, "Defaults"): nearer walls of an
    // interior clip. Unless --exposure says otherwise, such a frame is shown at --exposure auto.
    if (!options.exposure_given && scene.default_headlight) settings.exposure.automatic = true;
    return settings;
}

// The frame's outputs: --out, --dump-hits, --heatmap (its scale joins the stats), --pixel's ray tree.
void write_frame(const std::string& stage, const Options& options, const Scene& scene, const RenderSettings& settings,
                 int frame, FrameResult& result, RunOutputs& files, const std::string& path) {
    if (!path.empty()) {
        files.write({"--out", path}, [&](const std::string& file) {
            write_image_file(file, apply_exposure(result.image, settings.exposure));   // display only
        });
        if (!settings.exposure.is_identity())   // the EV the image was saved with (auto: this frame's)
            result.extra["exposure"] = {
                {"auto", settings.exposure.automatic},
                {"ev", settings.exposure.automatic ? auto_exposure_ev(result.image) : settings.exposure.ev}};
    }
    if (!options.dump_hits.empty())
        files.write({"--dump-hits", frame_path(options.dump_hits, frame, options.frames)},
                    [&](const std::string& file) { write_hit_file(file, result.hits); });
    if (!options.heatmap.empty()) {
        const Heatmap heatmap = make_heatmap(result.tests_per_pixel, settings.width, settings.height,
                                             options.heatmap_scale, options.heatmap_max);
        files.write({"--heatmap", frame_path(options.heatmap, frame, options.frames)},
                    [&](const std::string& file) { write_image_file(file, heatmap.image); });
        result.extra["heatmap"] = heatmap_json(heatmap);
    }
    if (options.pixel) {
        const std::vector<RayTreeLine> tree =
            ray_tree(result.hits, result.ray_work, std::uint32_t(settings.watch_pixel));
        const std::uint64_t heatmap_value = result.tests_per_pixel.at(std::size_t(settings.watch_pixel));
        if (options.frames > 1) print(stage + ": frame " + std::to_string(frame) + "\n");
        print(format_ray_tree(tree, options.pixel->x, options.pixel->y, heatmap_value, result.ray_work_steps,
                              std::uint32_t(scene.lights.size()), settings.light_grid.n));
        result.extra["pixel"] =
            ray_tree_json(tree, options.pixel->x, options.pixel->y, heatmap_value, result.ray_work_steps);
    }
}

// What the frames added up to, for --stats.
struct RunTotals {
    FrameStats total;
    nlohmann::json frames = nlohmann::json::array();   // per frame, with --frames N > 1
    nlohmann::json last_extra;                         // the last frame's stage stats
    std::vector<std::string> effect_names;
    std::size_t dropped = 0;
};

void write_stats(const std::string& stage, const Options& options, const Input& in, const Scene& scene,
                 const std::string& renderer_name, const RunTotals& t, RunOutputs& files) {
    if (options.stats.empty()) return;
    nlohmann::json extra = {{"triangles", scene.triangle_count()},
                            {"lights", scene.lights.size()},
                            {"area_lights", scene.area_lights.size()},
                            {"defaults", {{"camera", scene.default_camera}, {"light", scene.default_light},
                                          {"headlight", scene.default_headlight}, {"world", scene.default_world}}},
                            {"ambient", ambient_name(scene.ambient)},
                            {"dropped_triangles", t.dropped},
                            {"settings", settings_json(options.render)},
                            {"threads", resolve_thread_count(options.render.threads)},
                            {"frames", options.frames}};
    if (in.environment)
        extra["environment"] = {{"file", in.environment->file}, {"width", in.environment->width},
                                {"height", in.environment->height},
                                {"rotation_degrees", in.environment->rotation_degrees},
                                {"intensity", in.environment->intensity}};
    if (options.frames > 1) extra["frame_stats"] = t.frames;
    if (t.last_extra.is_object()) extra.update(t.last_extra);
    const nlohmann::json json = make_stats_json(stage, scene_label(options.scene), options.render.width,
                                                options.render.height, renderer_name, t.effect_names, t.total, extra);
    files.write({"--stats", options.stats}, [&](const std::string& file) { write_json_file(file, json); });
}

int run(const std::string& stage, int argc, char** argv, Renderer& renderer) {
    CLI::App app{stage + ": one stage of the ray-tracing course (see " + stage + "/README.md)", stage};
    Options options;
    if (const std::optional<int> done = parse_command_line(app, stage, argc, argv, renderer, options)) return *done;
    const Input in = load_input(stage, options);
    RunOutputs files;
    reserve_outputs(options, in.asset, files);
    if (export_scene(stage, options, in.asset, files)) {
        files.keep();
        return 0;
    }

    renderer.initialize();
    const std::string label = scene_label(options.scene);
    RunTotals totals;
    Scene scene;
    float duration = 0.0f;
    for (const Animation& a : in.asset.animations) duration = std::max(duration, a.duration());
    // Past the requested frames only an interactive window keeps going: nothing more is written, and animated
    // scenes loop.
    for (int frame = 0; frame < options.frames || renderer.interactive(); ++frame) {
        const bool shown_only = frame >= options.frames;
        float time = float(frame / options.fps);
        // A still scene is the same in every frame: flattened once, and kept on the GPU by the GPU stages.
        if (frame == 0 || scene.animated) scene = frame_scene(stage, options, in, frame, duration, totals.dropped, time);
        if (frame == 0 && !scene.animated) scene.still_id = next_still_id();
        const RenderSettings settings = frame_settings(options, scene, shown_only);
        totals.effect_names = settings.effects.names();
        if (frame == 0)
            if (const std::string why = renderer.unsupported(scene, settings); !why.empty()) throw InputError(why);
        const auto start = std::chrono::steady_clock::now();
        FrameResult result = renderer.render(scene, settings);
        const auto elapsed = std::chrono::steady_clock::now() - start;
        result.stats.total_ms = std::chrono::duration<double, std::milli>(elapsed).count();
        if (shown_only) continue;

        const std::string path = options.out.empty() ? "" : frame_path(options.out, frame, options.frames);
        write_frame(stage, options, scene, settings, frame, result, files, path);
        if (!options.render.quiet) print_summary(stage, label, settings, result.stats, path);
        totals.total.add(result.stats);
        if (options.frames > 1) {
            // Per frame also what the CPU asked of the GPU (a GPU stage's counters), which differs from frame to frame
            // (a still scene is uploaded with the first only).
            nlohmann::json per_frame = {{"time_s", time}};
            for (const char* key : {"gl_dispatches", "read_backs", "upload_bytes"})
                if (result.extra.contains(key)) per_frame[key] = result.extra[key];
            totals.frames.push_back(make_stats_json(stage, label, settings.width, settings.height,
                                                    renderer.renderer_name(), totals.effect_names, result.stats,
                                                    per_frame));
        }
        totals.last_extra = result.extra;
    }
    write_stats(stage, options, in, scene, renderer.renderer_name(), totals, files);
    files.keep();
    return 0;
}

}  // namespace

std::string one_printable_line(const std::string& message) {
    std::string text = message;
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    std::string out;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else if (u < 0x20 || u == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", u);
            out += hex;
        } else {
            out += c;
        }
    }
    return out;
}

int run_stage(const std::string& stage, int argc, char** argv, Renderer& renderer) {
    std::signal(SIGPIPE, SIG_IGN);   // a closed stdout is an error on write (see print), not the end of the run
    // A write past a file-size limit (`ulimit -f`) fails with EFBIG and is reported as every failed write (one line,
    // exit 1, the temporary removed), instead of SIGXFSZ ending the run with its temporary left behind.
    std::signal(SIGXFSZ, SIG_IGN);
    // An error is one line whatever a file name in it holds: control characters are written as escapes.
    const auto error = [&](const std::exception& e) {
        std::cerr << stage << ": error: " << one_printable_line(e.what()) << "\n";
    };
    try {
        return run(stage, argc, argv, renderer);
    } catch (const InputError& e) {
        error(e);
        return 2;
    } catch (const SceneError& e) {
        error(e);
        return 2;
    } catch (const std::exception& e) {
        error(e);
        return 1;
    }
}

}  // namespace rt
