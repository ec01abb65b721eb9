#include "grid_options.h"

#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "common/app/options.h"

namespace rt {

glm::ivec3 parse_grid_res(const std::string& text) {
    glm::ivec3 res;
    std::istringstream in(text);
    char c1 = 0, c2 = 0;
    if (!(in >> res.x >> c1 >> res.y >> c2 >> res.z) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof())
        throw std::invalid_argument("'" + text + "': expected X,Y,Z (three positive integers)");
    for (int a = 0; a < 3; ++a)
        if (res[a] < 1 || res[a] > kMaxGridResPerAxis)
            throw std::invalid_argument("'" + text + "': each axis must be in 1.." +
                                        std::to_string(kMaxGridResPerAxis));
    return res;
}

void add_grid_options(CLI::App& app, GridOptions& options) {
    app.add_option("--grid-lambda", options.lambda,
                   "Grid cells per triangle for the resolution heuristic (changes the cost, never the image)")
        ->capture_default_str()
        ->check(number_in(1e-3, 1e3));   // finite: NaN and Inf are refused
    app.add_option_function<std::string>(
           "--grid-res", [&options](const std::string& s) { options.res = parse_grid_res(s); },
           "Grid resolution X,Y,Z instead of the heuristic")
        ->check(CLI::Validator(
            [](std::string& s) {
                try {
                    parse_grid_res(s);
                    return std::string();
                } catch (const std::invalid_argument& e) {
                    return std::string(e.what());
                }
            },
            "X,Y,Z"));
    app.add_option_function<std::string>(
           "--primary", [&options](const std::string& s) { options.trace_primary = s == "trace"; },
           "Primary rays: raster (stage 02's G-buffer, default) or trace (camera rays through the grid)")
        ->check(CLI::IsMember({"raster", "trace"}));
}

}  // namespace rt
