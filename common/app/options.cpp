#include "options.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/scene/builtin/builtin_scenes.h"
#include "common/scene/effects.h"
#include "environment_file.h"
#include "image.h"

namespace rt {

namespace {

std::string readable(double v) {
    std::ostringstream out;
    out.precision(10);
    out << v;   // "16384", "0.001", "2147483647": never the 309 digits of std::to_string(DBL_MAX)
    return out.str();
}

}  // namespace

namespace {

// What every number on the command line must look like before it is read: no blanks anywhere (strtod would skip
// leading ones and CLI11 would then refuse the value without saying why), no hexadecimal ("0x10" is 16 to strtod),
// no "inf" or "nan".
std::string refuse_shape(const std::string& text) {
    if (text.empty()) return "the value is empty (expected a number)";
    if (std::any_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); }))
        return "'" + text + "' holds a blank (expected a number)";
    if (text.find_first_of("xX") != std::string::npos) return "'" + text + "' is not a decimal number";
    return {};
}

}  // namespace

CLI::Validator number_in(double lo, double hi, bool exclusive_lo) {
    const std::string bounds = (exclusive_lo ? "above " : "at least ") + readable(lo) + " and at most " + readable(hi);
    const std::string description = "NUMBER " + bounds;
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            if (std::string why = refuse_shape(text); !why.empty()) return why;
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0') return "'" + text + "' is not a number";
            if (!std::isfinite(v) || (errno == ERANGE && std::fabs(v) > 1.0)) return text + " is not a finite number";
            if (v < lo || v > hi || (exclusive_lo && v == lo)) return text + " is out of range: must be " + bounds;
            // Hand CLI11 the number in one spelling it reads back exactly (17 digits round-trip a double).
            char exact[40];
            std::snprintf(exact, sizeof exact, "%.17g", v == 0.0 ? 0.0 : v);
            text = exact;
            return std::string();
        },
        description);
}

CLI::Validator whole_number_in(long long lo, long long hi) {
    const std::string bounds = "at least " + std::to_string(lo) + " and at most " + std::to_string(hi);
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            if (std::string why = refuse_shape(text); !why.empty()) return why;
            const std::size_t digits = text[0] == '-' || text[0] == '+' ? 1 : 0;
            if (digits == text.size() || text.find_first_not_of("0123456789", digits) != std::string::npos)
                return "'" + text + "' is not a whole number";
            errno = 0;
            char* end = nullptr;
            const long long v = std::strtoll(text.c_str(), &end, 10);   // base 10: "010" is 10, not octal 8
            if (errno == ERANGE || v < lo || v > hi) return text + " is out of range: must be " + bounds;
            text = std::to_string(v);   // "-0" and "+08" become "0" and "8": CLI11 reads a leading 0 as octal
            return std::string();
        },
        "WHOLE NUMBER " + bounds);
}

CLI::Validator whole_number_of(const std::vector<long long>& allowed) {
    std::string list;
    for (std::size_t i = 0; i < allowed.size(); ++i)
        list += (i == 0 ? "" : i + 1 == allowed.size() ? " or " : ", ") + std::to_string(allowed[i]);
    const CLI::Validator whole = whole_number_in(LLONG_MIN, LLONG_MAX);
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            if (std::string why = whole(text); !why.empty()) return why;
            if (std::find(allowed.begin(), allowed.end(), std::stoll(text)) == allowed.end())
                return text + " is not one of " + list;
            return std::string();
        },
        "ONE OF " + list);
}

namespace {

// A validator from a parser that throws std::invalid_argument: its message is the reason the value is refused.
template <class Parse>
CLI::Validator parsed_by(Parse parse, const std::string& name) {
    return CLI::Validator(
        [parse](std::string& text) {
            try {
                parse(text);
            } catch (const std::invalid_argument& e) {
                return std::string(e.what());
            }
            return std::string();
        },
        name);
}

}  // namespace

glm::ivec2 parse_pixel(const std::string& text) {
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
        throw std::invalid_argument("'" + text + "' is not X,Y (two whole numbers separated by a comma)");
    glm::ivec2 p(0);
    for (int k = 0; k < 2; ++k) {
        const std::string part = k == 0 ? text.substr(0, comma) : text.substr(comma + 1);
        if (part.empty() || part.size() > 5 || part.find_first_not_of("0123456789") != std::string::npos)
            throw std::invalid_argument("'" + text + "' is not X,Y: '" + part + "' is not a whole number from 0 to " +
                                        std::to_string(kMaxImageSide - 1));
        p[k] = std::stoi(part);
        if (p[k] >= kMaxImageSide)
            throw std::invalid_argument("'" + text + "': " + part + " is out of range: must be at most " +
                                        std::to_string(kMaxImageSide - 1));
    }
    return p;
}

glm::vec3 parse_background(const std::string& text) {
    glm::vec3 c(0.0f);
    if (text == "black") return c;   // rays that leave the scene bring back nothing
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t comma = text.find(',', start);
        if ((k < 2) != (comma != std::string::npos))
            throw std::invalid_argument("'" + text + "' is not R,G,B (three numbers separated by commas)");
        const std::string part = text.substr(start, k < 2 ? comma - start : std::string::npos);
        char* end = nullptr;
        const double v = std::strtod(part.c_str(), &end);
        if (part.empty() || end != part.c_str() + part.size())
            throw std::invalid_argument("'" + text + "' is not R,G,B: '" + part + "' is not a number");
        if (!std::isfinite(v)) throw std::invalid_argument("'" + text + "': " + part + " is not a finite number");
        if (v < 0.0 || v > double(kMaxRadiance))
            throw std::invalid_argument("'" + text + "': " + part + " is out of range: must be at least 0 and at most 1e+20");
        c[k] = float(v);
        start = comma + 1;
    }
    return c;
}

void add_shared_options(CLI::App& app, Options& o) {
    app.add_option("--scene", o.scene, "builtin:NAME (" + builtin_scene_list() + ") or a .gltf/.glb file")
        ->capture_default_str();
    app.add_option("--width", o.render.width, "Image width in pixels")
        ->capture_default_str()
        ->check(whole_number_in(1, kMaxImageSide));
    app.add_option("--height", o.render.height, "Image height in pixels")
        ->capture_default_str()
        ->check(whole_number_in(1, kMaxImageSide));
    app.add_option("--out", o.out, ".png/.jpg (sRGB 8-bit) or .exr/.hdr (linear float); with --frames, w.png writes w_0000.png, ...");
    app.add_option("--camera", o.camera, "glTF camera index (default: the first camera, else an auto-framed one)")
        ->check(whole_number_in(0, INT_MAX));
    app.add_option("--max-depth", o.render.max_depth, "Whitted recursion depth (0 = no reflection/refraction rays)")
        ->capture_default_str()->check(whole_number_in(0, 64));
    app.add_option("--effects", o.effects,
                   "auto (what the scene calls for), all, none, or a comma list of shadows,reflections,refractions,textures,absorption,normal_maps,cutouts,blend")
        ->capture_default_str()
        ->check(CLI::Validator([](std::string& s) { return is_valid_effects_spec(s) ? std::string() : "unknown effect in '" + s + "'"; }, "EFFECTS"));
    app.add_option("--stats", o.stats, "Write the frame's statistics as JSON");
    app.add_flag("--quiet", o.render.quiet, "No progress bar or summary line");
    app.add_option("--threads", o.render.threads, "CPU threads (0 = all)")->capture_default_str()->check(whole_number_in(0, 1024));
    app.add_option("--export", o.export_path, "Write the scene as glTF 2.0 (.gltf or .glb) to open it in Blender");
    // Diagnostics (with --frames, one file per frame like --out).
    app.add_option("--dump-hits", o.dump_hits, "Write every traced ray and its hit to FILE (common/trace/hit_record.h)");
    app.add_option("--heatmap", o.heatmap, "Write a false-colour image of the ray/triangle tests per pixel to FILE");
    app.add_option_function<std::string>(
           "--pixel", [&o](const std::string& text) { o.pixel = parse_pixel(text); },
           "X,Y: print that pixel's ray tree (each ray, its hit and the tests it cost); 0,0 is the top left")
        ->check(parsed_by(parse_pixel, "X,Y"));
    add_enum(app, "--heatmap-scale", o.heatmap_scale, {{"linear", HeatmapScale::Linear}, {"log", HeatmapScale::Log}},
             "Colour scale of --heatmap");
    app.add_option("--heatmap-max", o.heatmap_max,
                   "Top of --heatmap's scale (from 0; larger counts take the top colour), to compare two heatmaps")
        ->check(whole_number_in(1, 4000000000));
    app.add_option("--frames", o.frames, "Number of frames for animated scenes (at most 10000)")->capture_default_str()
        ->check(whole_number_in(1, kMaxFrames));
    app.add_option("--fps", o.fps, "Frames per second (frame i is rendered at t = i / fps)")->capture_default_str()
        ->check(number_in(1e-3, 1e4));
    app.add_option("--max-triangles", o.max_triangles, "Refuse scenes with more triangles per frame than this")
        ->capture_default_str()->check(whole_number_in(1, 4000000000));
    // Accuracy knobs (docs/accuracy.md measures what each costs).
    add_enum(app, "--intersect", o.render.intersect,
             {{"moller", IntersectMethod::Moller}, {"watertight", IntersectMethod::Watertight}},
             "Ray/triangle test: moller (Moller-Trumbore) or watertight (Woop et al. 2013)");
    add_enum(app, "--offset", o.render.offset, {{"epsilon", OffsetMethod::Epsilon}, {"robust", OffsetMethod::Robust}},
             "Secondary ray origins: a fixed epsilon or the robust offset of Waechter & Binder 2019");
    app.add_option("--epsilon", o.render.epsilon, "The fixed offset of --offset epsilon, in scene units")
        ->capture_default_str()->check(number_in(0, 1e6, true));
    add_enum(app, "--fresnel", o.render.fresnel, {{"schlick", FresnelMode::Schlick}, {"exact", FresnelMode::Exact}},
             "Fresnel reflectance: Schlick's approximation or the exact dielectric formula");
    app.add_option("--cutoff", o.render.cutoff, "Stop a path when its weight is below this in every channel")
        ->capture_default_str()->check(number_in(0, 1));
    // Display (exposure.h, docs/shading.md "Exposure"): applied to the saved and shown image, never to the lighting.
    app.add_option_function<std::string>(
           "--exposure", [&o](const std::string& text) {
               const ToneCurve curve = o.render.exposure.curve;   // --tone-curve may come first
               o.render.exposure = parse_exposure(text);
               o.render.exposure.curve = curve;
               o.exposure_given = true;
           },
           "Scale the output by 2^EV (EV in [-20, 20]; 0 = unchanged), or auto: the 99th percentile luminance to 1; "
           "default 0, or auto for a scene lit by the default headlight")
        ->default_str("0")
        ->check(CLI::Validator(
            [](std::string& text) {
                try {
                    parse_exposure(text);
                } catch (const std::invalid_argument& e) {
                    return std::string(e.what());
                }
                return std::string();
            },
            "EV|auto"));
    add_enum(app, "--tone-curve", o.render.exposure.curve, {{"none", ToneCurve::None}, {"aces", ToneCurve::Aces}},
             "After --exposure: none (linear, clips at 1) or aces (filmic shoulder, Narkowicz 2015)");
    // Rays that leave the scene (docs/shading.md, "The environment"): background, not lighting.
    app.add_option_function<std::string>(
           "--background", [&o](const std::string& text) { o.background = parse_background(text); },
           "R,G,B or black: linear radiance of rays that leave the scene, instead of the scene's (glTF files: the "
           "default world, a grey studio)")
        ->check(parsed_by(parse_background, "R,G,B"));
    app.add_option_function<std::string>(
           "--ambient",
           [&o](const std::string& word) {
               o.ambient = word == "none" ? AmbientModel::None
                                          : (word == "hemisphere" ? AmbientModel::Hemisphere : AmbientModel::Constant);
           },
           "Ambient light (no rays; docs/shading.md, \"Ambient\"): constant, hemisphere (brighter from above) or none; "
           "default: the scene's (built-in scenes constant, glTF files hemisphere)")
        ->transform(CLI::IsMember({"none", "constant", "hemisphere"}, CLI::ignore_case));
    CLI::Option* environment =
        app.add_option("--environment", o.environment,
                       "Equirectangular .hdr/.exr map that rays leaving the scene see (not a light); replaces the background");
    app.add_option("--environment-rotation", o.environment_rotation, "Turn the --environment map by DEGREES about +Y")
        ->capture_default_str()->check(number_in(-kMaxEnvironmentRotation, kMaxEnvironmentRotation))->needs(environment);
    app.add_option("--environment-intensity", o.environment_intensity, "Scale the --environment map's radiance")
        ->capture_default_str()->check(number_in(0, kMaxEnvironmentIntensity))->needs(environment);
    // Area lights (docs/shading.md, "Area lights"): which emitters light the scene, and how each is sampled.
    add_enum(app, "--area-lights", o.area_lights,
             {{"auto", AreaLightMode::Auto}, {"all", AreaLightMode::All}, {"off", AreaLightMode::Off}},
             "Emissive surfaces that light the scene: auto (those brighter than white), all, or off (they only glow)");
    app.add_option("--light-grid", o.render.light_grid.n,
                   "N: each hit sends N x N shadow rays to each area light, one through each cell of a grid over it")
        ->capture_default_str()->check(whole_number_in(1, kMaxLightGrid));
    app.add_flag("--light-jitter", o.render.light_grid.jitter,
                 "Shift each area light's grid within its cells by an offset seeded by the pixel and its sample");
    app.add_option("--spp", o.render.spp, "Samples per pixel (anti-aliasing)")->capture_default_str()->check(whole_number_in(1, 4096));
}

void validate_options(const Options& o) {
    namespace fs = std::filesystem;
    if (!o.heatmap.empty() && !is_supported_image_path(o.heatmap))
        throw std::invalid_argument("unsupported image type for --heatmap: " + o.heatmap + " (use " + supported_image_types() + ")");
    // A ray's path number doubles per bounce (hit_record.h) and must fit 31 bits.
    if (!o.dump_hits.empty() && o.render.max_depth > 30)
        throw std::invalid_argument("--dump-hits needs --max-depth 30 or less (ray path numbers have 31 bits)");
    if (o.pixel && o.render.max_depth > 30)
        throw std::invalid_argument("--pixel needs --max-depth 30 or less (ray path numbers have 31 bits)");
    if (o.pixel && (o.pixel->x >= o.render.width || o.pixel->y >= o.render.height))
        throw std::invalid_argument("--pixel " + std::to_string(o.pixel->x) + "," + std::to_string(o.pixel->y) +
                                    " is outside the " + std::to_string(o.render.width) + "x" +
                                    std::to_string(o.render.height) + " image (x from 0 to " +
                                    std::to_string(o.render.width - 1) + ", y from 0 to " +
                                    std::to_string(o.render.height - 1) + ")");
    if (!o.out.empty() && !is_supported_image_path(o.out))
        throw std::invalid_argument("unsupported image type for --out: " + o.out + " (use " + supported_image_types() + ")");
    if (!o.export_path.empty()) {
        // Extensions pick a format in any case, for every option (--out o.PNG, --export x.GLB; README "Outputs").
        std::string ext = fs::path(o.export_path).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (ext != ".gltf" && ext != ".glb") throw std::invalid_argument("--export needs a .gltf or .glb file: " + o.export_path);
    }
    const double pixels = double(o.render.width) * double(o.render.height);
    if (pixels > 64.0 * 1024 * 1024) throw std::invalid_argument("image too large: at most 64 Mpixels");
    // Each bound alone is a sensible image, but 64 Mpixels at 4096 samples is 2.7e11 primary rays, months of stage
    // 01: a frame may have at most 2^32 samples (640x480 or 1024x1024 at 4096 spp, 64 Mpixels at 64).
    const double samples = pixels * double(o.render.spp);
    if (samples > 4294967296.0) {
        std::string why = "--spp ";
        why += std::to_string(o.render.spp) + " at " + std::to_string(o.render.width) + "x" +
               std::to_string(o.render.height) + " is " + std::to_string(std::uint64_t(samples)) +
               " samples a frame: at most 4294967296 (2^32); lower --spp or the image size";
        throw std::invalid_argument(why);
    }
}

std::vector<OutputPath> planned_outputs(const Options& o) {
    std::vector<OutputPath> outputs;
    if (!o.export_path.empty()) outputs.push_back({"--export", o.export_path});
    if (!o.stats.empty()) outputs.push_back({"--stats", o.stats});
    // Per-frame outputs: one file per frame with --frames (frame_path).
    for (const auto& [option, path] : {std::pair<const char*, const std::string&>{"--out", o.out},
                                       {"--dump-hits", o.dump_hits}, {"--heatmap", o.heatmap}})
        if (!path.empty())
            for (int frame = 0; frame < o.frames; ++frame) outputs.push_back({option, frame_path(path, frame, o.frames)});
    return outputs;
}

std::string frame_path(const std::string& out, int frame, int count) {
    if (count <= 1) return out;
    const std::filesystem::path p(out);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%04d", frame);
    return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

}  // namespace rt
