// --pixel X,Y: one pixel's ray tree, printed for stepping through a ray in class. Each ray (of hit_record.h) with
// its kind, origin, direction and hit, and what it cost (RayWork: ray/triangle tests, and the traversal's own steps
// where it has them: 03's grid cells, 04-05's leaf pairs), children under their parent, shadow rays under the hit
// that spawned them. The tests add up to the pixel's heatmap value (every test has a pixel); the test
// cli.<stage>.pixel_ray_tree checks it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/trace/hit_record.h"

namespace rt {

struct RayTreeLine {
    HitRecord ray;
    std::uint64_t tests = 0, steps = 0;
    int depth = 0;   // indentation: bounces from the camera ray, shadow rays one more
};

// The pixel's rays in tree order (per sample: a ray, its shadow rays, its reflection subtree, its refraction
// subtree), each with the work reported under its name; work with no ray of that name is kept as a line whose
// ray has only the name (it would be a stage's bug, and the printout shows it).
std::vector<RayTreeLine> ray_tree(const std::vector<HitRecord>& hits, const std::vector<RayWork>& work,
                                  std::uint32_t pixel);

// The printout: a heading (pixel, rays, tests, the heatmap's value) and one line per ray. `steps_name` is what
// RayWork::steps counts in this stage ("" prints no steps). Lights from `punctual_lights` on are area lights with a
// `light_grid` x `light_grid` grid: their shadow rays are named by their light and cell, "light 2 cell (1, 3)".
std::string format_ray_tree(const std::vector<RayTreeLine>& lines, int x, int y, std::uint64_t heatmap_tests,
                            const std::string& steps_name, std::uint32_t punctual_lights = UINT32_MAX,
                            int light_grid = 1);

// The stats' "pixel" object: x, y, rays, tests, steps, steps_name, heatmap_tests.
nlohmann::json ray_tree_json(const std::vector<RayTreeLine>& lines, int x, int y, std::uint64_t heatmap_tests,
                             const std::string& steps_name);

}  // namespace rt
