// The hard cases of the 3D-DDA (walk_grid and its GLSL twin grid_walk.glsl), shared by the CPU test
// (uniform_grid_test.cpp) and the GLSL test (gpu_grid_test.cpp), each with its name.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "uniform_grid.h"

namespace rt::dda_cases {

struct DdaCase {
    std::string name;
    GridParams grid;
    glm::vec3 origin, direction;
    float tmax = std::numeric_limits<float>::infinity();
};

// A grid of res cells of size `cell` from `lo`.
inline GridParams grid(glm::ivec3 res, glm::vec3 lo = glm::vec3(0.0f), glm::vec3 cell = glm::vec3(1.0f)) {
    GridParams g;
    g.lo = lo;
    g.cell = cell;
    g.res = res;
    g.cell_count = std::uint32_t(res.x * res.y * res.z);
    return g;
}

inline std::vector<DdaCase> cases() {
    const GridParams g4 = grid(glm::ivec3(4));
    const float inf = std::numeric_limits<float>::infinity();
    return {
        {"ZeroDirectionComponents", g4, {-1.0f, 0.5f, 2.5f}, {1.0f, 0.0f, 0.0f}},
        {"NegativeZeroDirectionComponents", g4, {-1.0f, 0.5f, 2.5f}, {1.0f, -0.0f, -0.0f}},
        {"NegativeDirection", g4, {5.0f, 3.5f, 0.25f}, {-1.0f, -0.3f, 0.2f}},
        {"StartsOutsideTheGrid", g4, {-3.0f, -2.0f, -1.0f}, {1.0f, 0.9f, 0.8f}},
        {"StartsInsideTheGrid", g4, {1.5f, 2.5f, 0.5f}, {0.3f, -0.5f, 0.8f}},
        {"MissesTheGrid", g4, {-1.0f, 5.0f, 0.5f}, {1.0f, 0.0f, 0.0f}},
        {"MissesTheGridWithAZeroComponent", g4, {0.5f, 4.5f, -1.0f}, {0.0f, 0.0f, 1.0f}},
        {"StartsOnACellBoundary", g4, {2.0f, 1.5f, 1.5f}, {1.0f, 0.25f, 0.0f}},
        {"StartsOnACellBoundaryGoingBack", g4, {2.0f, 1.5f, 1.5f}, {-1.0f, 0.25f, 0.0f}},
        {"StartsOnAGridCorner", g4, {0.0f, 0.0f, 0.0f}, {1.0f, 2.0f, 3.0f}},
        {"EntersThroughAGridCorner", g4, {-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}},
        {"RunsInsideAGridPlane", g4, {-1.0f, 2.0f, 0.5f}, {1.0f, 0.0f, 0.5f}},
        {"RunsAlongAGridEdge", g4, {-1.0f, 2.0f, 3.0f}, {1.0f, 0.0f, 0.0f}},
        {"RunsOnTheGridsOuterFace", g4, {-1.0f, 0.0f, 1.5f}, {1.0f, 0.0f, 0.0f}},
        {"TiesBetweenTwoAxes", g4, {0.5f, 0.5f, 1.5f}, {1.0f, 1.0f, 0.0f}},
        {"TiesBetweenThreeAxes", g4, {0.5f, 0.5f, 0.5f}, {1.0f, 1.0f, 1.0f}},
        {"StopsAtTmax", g4, {0.5f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}, 1.75f},
        {"OneCellGrid", grid(glm::ivec3(1)), {-2.0f, 0.25f, 0.75f}, {1.0f, 0.1f, -0.1f}},
        {"FlatGrid", grid(glm::ivec3(8, 1, 8), glm::vec3(0.0f), glm::vec3(0.5f, 1e-3f, 0.5f)), {-1.0f, 5e-4f, 0.1f},
         {1.0f, 0.0f, 0.45f}},
        {"FarFromTheOrigin", grid(glm::ivec3(16), glm::vec3(1e5f, -2e5f, 3e5f), glm::vec3(0.25f)),
         {1e5f - 1.0f, -2e5f + 1.0f, 3e5f + 2.0f}, {1.0f, 0.6f, -0.3f}},
        {"VeryLongRayFromFarAway", grid(glm::ivec3(32, 8, 16)), {-1e4f, 3.3f, 7.7f}, {1.0f, 1e-7f, 1e-6f}},
        {"AxisAlignedDown", g4, {1.5f, 10.0f, 2.5f}, {0.0f, -1.0f, 0.0f}, inf},
    };
}

}  // namespace rt::dda_cases
