// The command line every stage shares (defined once here, with CLI11).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "renderer.h"

namespace rt {

struct Options {
    std::string scene = "builtin:whitted";   // builtin:NAME, FILE.gltf or FILE.glb
    std::string out;                          // image file; empty = no image
    std::string stats;                        // stats JSON file; empty = none
    std::string export_path;                  // write the scene as glTF
    std::string effects = "auto";
    int camera = -1;
    int frames = 1;
    double fps = 24.0;
    RenderSettings render;
};

// Adds every shared option to `app`, bound to `options`.
void add_shared_options(CLI::App& app, Options& options);

// Checks what CLI11's validators cannot (combinations, output paths). Throws std::invalid_argument with one line.
void validate_options(const Options& options);

// Image file for frame `frame` of `count`: "w.png" for one frame, "w_0003.png" for frame 3 of many.
std::string frame_path(const std::string& out, int frame, int count);

}  // namespace rt
