// Stage 03's command-line options: what a student may change about the grid (its resolution) and which rays it
// walks. The renderer reads the struct; add_grid_options declares it to the command line (CLI11).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "uniform_grid.h"

namespace CLI { class App; }

namespace rt {

struct GridOptions {
    float lambda = kDefaultGridLambda;   // --grid-lambda: cells per triangle (resolution heuristic)
    glm::ivec3 res{0};                   // --grid-res X,Y,Z (0 = from the heuristic)
    bool trace_primary = false;          // --primary trace (default raster)
};

// --grid-lambda, --grid-res and --primary, written into `options` when parsed.
void add_grid_options(CLI::App& app, GridOptions& options);

// Parses "X,Y,Z" (each 1..kMaxGridResPerAxis); throws std::invalid_argument with a one-line message otherwise.
glm::ivec3 parse_grid_res(const std::string& text);

}  // namespace rt
