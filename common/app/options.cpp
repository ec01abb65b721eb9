#include "options.h"

#include <filesystem>
#include <map>
#include <stdexcept>
#include <vector>

#include "../scene/effects.h"
#include "image.h"

namespace rt {

void add_shared_options(CLI::App& app, Options& o) {
    app.add_option("--scene", o.scene, "builtin:NAME (whitted, cornell, diffuse, dynamic, spheres:N, far) or a .gltf/.glb file")
        ->capture_default_str();
    app.add_option("--width", o.render.width, "Image width in pixels")->capture_default_str()->check(CLI::Range(1, 16384));
    app.add_option("--height", o.render.height, "Image height in pixels")->capture_default_str()->check(CLI::Range(1, 16384));
    app.add_option("--out", o.out, ".png/.jpg (sRGB 8-bit) or .exr/.hdr (linear float); with --frames, w.png writes w_0000.png, ...");
    app.add_option("--camera", o.camera, "glTF camera index (default: the first camera, else an auto-framed one)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--max-depth", o.render.max_depth, "Whitted recursion depth (0 = no reflection/refraction rays)")
        ->capture_default_str()->check(CLI::Range(0, 64));
    app.add_option("--effects", o.effects,
                   "auto (what the scene calls for), all, none, or a comma list of shadows,reflections,refractions,textures")
        ->capture_default_str()
        ->check(CLI::Validator([](std::string& s) { return is_valid_effects_spec(s) ? std::string() : "unknown effect in '" + s + "'"; }, "EFFECTS"));
    app.add_option("--stats", o.stats, "Write the frame's statistics as JSON");
    app.add_flag("--quiet", o.render.quiet, "No progress bar or summary line");
    app.add_option("--threads", o.render.threads, "CPU threads (0 = all)")->capture_default_str()->check(CLI::Range(0, 1024));
    app.add_option("--export", o.export_path, "Write the scene as glTF 2.0 (.gltf or .glb) to open it in Blender");
    app.add_option("--frames", o.frames, "Number of frames for animated scenes")->capture_default_str()->check(CLI::Range(1, 100000));
    app.add_option("--fps", o.fps, "Frames per second (frame i is rendered at t = i / fps)")->capture_default_str()
        ->check(CLI::Range(1e-3, 1e4));
    app.add_option("--max-triangles", o.max_triangles, "Refuse scenes with more triangles per frame than this")
        ->capture_default_str()->check(CLI::PositiveNumber);
    // Accuracy knobs (docs/accuracy.md measures what each costs).
    add_enum(app, "--intersect", o.render.intersect,
             {{"moller", IntersectMethod::Moller}, {"watertight", IntersectMethod::Watertight}},
             "Ray/triangle test: moller (Moller-Trumbore) or watertight (Woop et al. 2013)");
    add_enum(app, "--offset", o.render.offset, {{"epsilon", OffsetMethod::Epsilon}, {"robust", OffsetMethod::Robust}},
             "Secondary ray origins: a fixed epsilon or the robust offset of Waechter & Binder 2019");
    app.add_option("--epsilon", o.render.epsilon, "The fixed offset of --offset epsilon, in scene units")
        ->capture_default_str()->check(CLI::PositiveNumber);
    add_enum(app, "--fresnel", o.render.fresnel, {{"schlick", FresnelMode::Schlick}, {"exact", FresnelMode::Exact}},
             "Fresnel reflectance: Schlick's approximation or the exact dielectric formula");
    app.add_option("--cutoff", o.render.cutoff, "Stop a path when its weight is below this in every channel")
        ->capture_default_str()->check(CLI::Range(0.0, 1.0));
    app.add_option("--spp", o.render.spp, "Samples per pixel (anti-aliasing)")->capture_default_str()->check(CLI::Range(1, 4096));
}

void validate_options(const Options& o) {
    namespace fs = std::filesystem;
    auto check_output = [&](const std::string& path, const std::string& what) {
        if (path.empty()) return;
        const fs::path p(path);
        const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
        if (!fs::is_directory(dir)) throw std::invalid_argument(what + " folder does not exist: " + dir.string());
        if (fs::is_directory(p)) throw std::invalid_argument(what + " is a folder: " + path);
        // Never overwrite the input.
        if (!o.scene.starts_with("builtin:") && fs::exists(p) && fs::exists(o.scene) && fs::equivalent(p, o.scene))
            throw std::invalid_argument(what + " would overwrite the input scene: " + path);
    };
    check_output(o.out, "--out");
    check_output(o.stats, "--stats");
    check_output(o.export_path, "--export");
    if (!o.out.empty() && !is_supported_image_path(o.out))
        throw std::invalid_argument("unsupported image type for --out: " + o.out + " (use " + supported_image_types() + ")");
    if (!o.export_path.empty()) {
        const std::string ext = fs::path(o.export_path).extension().string();
        if (ext != ".gltf" && ext != ".glb") throw std::invalid_argument("--export needs a .gltf or .glb file: " + o.export_path);
    }
    const double pixels = double(o.render.width) * double(o.render.height);
    if (pixels > 64.0 * 1024 * 1024) throw std::invalid_argument("image too large: at most 64 Mpixels");
}

std::string frame_path(const std::string& out, int frame, int count) {
    if (count <= 1) return out;
    const std::filesystem::path p(out);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%04d", frame);
    return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

}  // namespace rt
