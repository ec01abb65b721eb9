// The command line every stage shares (defined once here, with CLI11).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "output_files.h"
#include "heatmap.h"
#include "renderer.h"

namespace rt {

// Upper limits of the count options, so a typo cannot ask for days of rendering or millions of files.
constexpr int kMaxFrames = 10000;

struct Options {
    std::string scene = "builtin:whitted";   // builtin:NAME, FILE.gltf or FILE.glb
    std::string out;                          // image file; empty = no image
    std::string stats;                        // stats JSON file; empty = none
    std::string export_path;                  // write the scene as glTF
    std::string dump_hits;                    // --dump-hits: every traced ray and its hit (hit_record.h)
    std::string heatmap;                      // --heatmap: false-colour ray/triangle tests per pixel (heatmap.h)
    std::optional<glm::ivec2> pixel;          // --pixel X,Y: print that pixel's ray tree (ray_tree.h)
    HeatmapScale heatmap_scale = HeatmapScale::Linear;
    std::uint32_t heatmap_max = 0;   // --heatmap-max (0: the image's own range)
    std::string effects = "auto";
    int camera = -1;
    int frames = 1;
    double fps = 24.0;
    std::uint64_t max_triangles = kDefaultMaxTriangles;   // FlattenOptions::max_triangles
    AreaLightMode area_lights = AreaLightMode::Auto;       // FlattenOptions::area_lights
    bool exposure_given = false;   // --exposure was given (else a frame lit by the default headlight gets auto)
    // What rays leaving the scene see (docs/shading.md, "The environment"): --background replaces the scene's
    // colour; --environment FILE (.hdr/.exr, equirectangular) replaces it by a map, turned and scaled by these.
    std::optional<glm::vec3> background;
    std::optional<AmbientModel> ambient;   // --ambient; unset: the scene's
    std::string environment;
    float environment_rotation = 0.0f;    // degrees about +Y
    float environment_intensity = 1.0f;
    RenderSettings render;
};

// An option whose value is one of a few words, stored as an enum. Errors name the words: "--offset: wrong not in
// {epsilon,robust}".
template <class E>
CLI::Option* add_enum(CLI::App& app, const std::string& name, E& value, const std::map<std::string, E>& names,
                      const std::string& help) {
    std::vector<std::string> words;
    std::string current;
    for (const auto& [word, v] : names) {
        words.push_back(word);
        if (v == value) current = word;
    }
    return app
        .add_option_function<std::string>(
            name, [&value, names](const std::string& word) { value = names.at(word); }, help)
        ->transform(CLI::IsMember(words, CLI::ignore_case))   // also turns "MOLLER" into "moller"
        ->default_str(current);
}

// The one validator of every numeric option (floating or integer): the value must be a finite number in [lo, hi], or
// in (lo, hi] when `exclusive_lo`. NaN and Inf are refused. Errors are one line with readable bounds:
// "--fps: nan is not a finite number", "--width: 0 is out of range: must be at least 1 and at most 16384".
// Blanks, hexadecimal and an empty value are refused too. The value is handed on rewritten as "%.17g".
CLI::Validator number_in(double lo, double hi, bool exclusive_lo = false);
// The same for integer options: only [+-]digits, read in base 10, in [lo, hi] ("4.0", "1e3", "" are refused with the
// reason; "08" is 8). Every integer option uses this or whole_number_of: CLI11's own conversion refuses without a
// reason, reads "010" as octal, and its IsMember let "" through as 0 (a division by zero in --branching).
CLI::Validator whole_number_in(long long lo, long long hi);
// An integer option with a few allowed values: whole_number_in's checks, then membership ("5 is not one of 4, 8 or 16").
CLI::Validator whole_number_of(const std::vector<long long>& allowed);

constexpr int kMaxImageSide = 16384;   // --width and --height at most

// --pixel's value: "X,Y", two whole numbers from 0 (in the image: validate_options). Throws std::invalid_argument.
glm::ivec2 parse_pixel(const std::string& text);

// --background's value: "black" or "R,G,B", three finite numbers in [0, kMaxRadiance] (linear radiance). Throws
// std::invalid_argument with one line otherwise.
glm::vec3 parse_background(const std::string& text);

// Adds every shared option to `app`, bound to `options`.
void add_shared_options(CLI::App& app, Options& options);

// Checks what CLI11's validators cannot (combinations, file types by name). Throws std::invalid_argument with one
// line. The output files themselves are checked by check_outputs(planned_outputs(...), ...), once the scene is loaded.
void validate_options(const Options& options);

// Every file the run will write, each --out frame on its own: the list check_outputs() compares with the inputs and
// with each other. A new output option adds its path here.
std::vector<OutputPath> planned_outputs(const Options& options);

// Image file for frame `frame` of `count`: "w.png" for one frame, "w_0003.png" for frame 3 of many.
std::string frame_path(const std::string& out, int frame, int count);

}  // namespace rt
